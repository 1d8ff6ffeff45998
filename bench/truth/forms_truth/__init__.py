# SPDX-License-Identifier: LGPL-3.0-or-later
"""UFL energy terms of the independent truth model (bench/truth).

Written separately from forms/ (the simulator's terms): nothing is imported
from there. One module per term; every effect module provides

    NAME, CANDIDATE        the truth model's name, and the breastsim candidate
                           it is closest to (calibrate/candidates.cpp)
    STRENGTH               (name, unit, first guess) of the strength parameter;
                           strength 0 is the effect-free truth
    draw_pattern(rng)      the effect's spatial shape (dict of floats), drawn
                           from documented ranges
    Term(ctx)              .energy (UFL), .set(pattern, strength),
                           .q_equivalent(pattern, strength) -> (value, note)
"""
from . import base_bed, gland_ellipsoid, skin_net, tethers  # noqa: F401

EFFECTS = {m.NAME: m for m in (base_bed, skin_net, tethers, gland_ellipsoid)}
