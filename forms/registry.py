# SPDX-License-Identifier: LGPL-3.0-or-later
"""The energy terms composed into the total energy, in order.

To add a physics term: write forms/<name>.py (NAME, PARAMETERS, ENERGY and
its Constants at module level; optionally FIT names for `--fit` and a
CANDIDATE for the missing-physics diagnosis, see forms/common.py) and add
one line here.
"""
TERMS = [
    "tissue",
    "gravity",
    "skin",
    "skin_upper_pole",
    "base_springs",
    "sutures",
    "suspensory_ligament",
    "suspensory_cables",
    "gland_core",
    "gland_lobe",
    "tissue_field",
    "tissue_law",
    "tissue_suture",
    "chest_wall",
]
