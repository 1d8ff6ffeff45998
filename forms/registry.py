"""The energy terms composed into the total energy, in order.

To add a physics term: write forms/<name>.py (NAME, PARAMETERS, ENERGY and
its Constants at module level) and add one line here.
"""
TERMS = [
    "tissue",
    "gravity",
    "skin",
    "base_springs",
    "sutures",
    "suspensory_ligament",
    "gland_core",
    "tissue_suture",
]
