# SPDX-License-Identifier: LGPL-3.0-or-later
"""UFL energy terms of the independent truth model (bench/truth).

Written separately from forms/ (the simulator's terms): nothing is imported
from there. One module per term; every effect module provides

    NAME, CANDIDATE        the truth model's name, and the breastsim candidate
                           it is closest to (calibrate/candidates.cpp); None for
                           an effect outside the candidate library, which has
    FAMILY, CLOSEST        instead the family of physics a discovery would name
                           (tissue_field, tissue_law, base_condition) and the
                           nearest candidate, if any (documentation only)
    STRENGTH               (name, unit, first guess) of the strength parameter;
                           strength 0 is the effect-free truth
    draw_pattern(rng)      the effect's spatial shape (dict of floats), drawn
                           from documented ranges
    Term(ctx)              .energy (UFL), .set(pattern, strength),
                           .q_equivalent(pattern, strength) -> (value, note),
                           None without a candidate

EFFECTS holds the effects inside the candidate family (IN_LIBRARY, the sets
main ... glandform) and those outside it (OUTSIDE_LIBRARY, the set outside).
"""
from . import (base_bed, gland_ellipsoid, mooney_rivlin, skin_net, sliding_base,  # noqa: F401
               stiff_inclusion, stiffness_gradient, strain_stiffening, tethers)

IN_LIBRARY = (base_bed, skin_net, tethers, gland_ellipsoid)
OUTSIDE_LIBRARY = (stiff_inclusion, stiffness_gradient, strain_stiffening, mooney_rivlin, sliding_base)
EFFECTS = {m.NAME: m for m in IN_LIBRARY + OUTSIDE_LIBRARY}


def physics_of(name):
    """The physics a diagnosis should name for the hidden effect `name`: its
    breastsim candidate, or its family for an effect outside the library."""
    mod = EFFECTS[name]
    return mod.CANDIDATE if mod.CANDIDATE is not None else mod.FAMILY
