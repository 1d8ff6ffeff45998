#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""The three independent-truth benchmark sets (bench/truth/benchmark_set.py)
share no recording name and no noise seed, and have the documented sizes:
main 42 (14 controls), validation 12 (2 controls), holdout and confirm 12
each (4 controls, two weak shapes per candidate), effect 16 (4 controls,
three weak shapes per candidate), refine 15 (4 controls, eight weak beds,
one weak shape of each other candidate), tether 15 (4 controls, eight weak
tethers, four of them cables, one weak shape of each other candidate),
skinvar 14 (2 controls, eight skins, four of them stiffer on the upper
pole, four skin + tether pairs, two of them cables), glandform 14 (3
controls, eight weak glands, one weak shape of each other candidate);
every lambda/mu of
each set is in [2, 10].

Run: /usr/bin/python3 tests/truth/test_benchmark_sets.py SOURCE_DIR
"""
import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(sys.argv[1]) / "bench" / "truth"))
import benchmark_set  # noqa: E402

SIZES = {"main": (42, 14), "validation": (12, 2), "holdout": (12, 4), "confirm": (12, 4), "effect": (16, 4),
         "refine": (15, 4), "tether": (15, 4), "skinvar": (14, 2),
         "glandform": (14, 3)}


def main():
    names, seeds = Counter(), Counter()
    for which, (size, controls) in SIZES.items():
        recs = benchmark_set.recordings(which)
        assert len(recs) == size, f"{which}: {len(recs)} recordings, expected {size}"
        n_controls = sum(r["strength_class"] == "control" for r in recs)
        assert n_controls == controls, f"{which}: {n_controls} controls, expected {controls}"
        for r in recs:
            names[r["name"]] += 1
            seeds[r["seed"]] += 1
            ratio = r["material"]["lambda"] / r["material"]["mu"]
            assert 2.0 <= ratio <= 10.0, f"{r['name']}: lambda/mu {ratio}"
    for which, shapes in (("holdout", 2), ("confirm", 2), ("effect", 3)):
        recs = benchmark_set.recordings(which)
        per_candidate = Counter(r["name"].rsplit("_weak_", 1)[0] for r in recs if r["strength_class"] == "weak")
        assert sorted(per_candidate.values()) == [shapes] * 4, (which, per_candidate)
    refine = Counter(r["name"].rsplit("_weak_", 1)[0] for r in benchmark_set.recordings("refine")
                     if r["strength_class"] == "weak")
    assert refine == {"ref_base_springs": 8, "ref_gland_core": 1, "ref_skin": 1, "ref_suspensory_ligament": 1}, refine
    assert set(SIZES) == set(benchmark_set.SETS), benchmark_set.SETS
    tether = benchmark_set.recordings("tether")
    variants = Counter(e[1]["variant"] for r in tether for e in r["effects"] if e[0] == "smooth_tethers")
    assert variants == {"springs": 4, "cables": 4}, variants
    others = Counter(r["name"].rsplit("_weak_", 1)[0] for r in tether if r["strength_class"] == "weak")
    assert others == {"teth_suspensory_ligament": 8, "teth_base_springs": 1, "teth_gland_core": 1,
                      "teth_skin": 1}, others
    skinvar = benchmark_set.recordings("skinvar")
    skins = [e[1] for r in skinvar for e in r["effects"] if e[0] == "fibre_net_skin"]
    assert len(skins) == 12 and sum(p["a_z"] > 0 for p in skins) == 6, skins
    variants = Counter(e[1]["variant"] for r in skinvar for e in r["effects"] if e[0] == "smooth_tethers")
    assert variants == {"springs": 2, "cables": 2}, variants
    glands = Counter(r["name"].rsplit("_weak_", 1)[0] for r in benchmark_set.recordings("glandform")
                     if r["strength_class"] == "weak")
    assert glands == {"glf_gland_core": 8, "glf_base_springs": 1, "glf_skin": 1,
                      "glf_suspensory_ligament": 1}, glands
    shared = [n for n, k in names.items() if k > 1] + [s for s, k in seeds.items() if k > 1]
    assert not shared, f"shared between sets: {shared}"
    print("benchmark sets: OK")


if __name__ == "__main__":
    main()
