#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""The independent-truth benchmark sets (bench/truth/benchmark_set.py)
share no recording name and no noise seed, and have the documented sizes:
main 42 (14 controls), validation 12 (2 controls), holdout and confirm 12
each (4 controls, two weak shapes per candidate), effect 16 (4 controls,
three weak shapes per candidate), refine 15 (4 controls, eight weak beds,
one weak shape of each other candidate), tether 15 (4 controls, eight weak
tethers, four of them cables, one weak shape of each other candidate),
skinvar 14 (2 controls, eight skins, four of them stiffer on the upper
pole, four skin + tether pairs, two of them cables), glandform 14 (3
controls, eight weak glands, one weak shape of each other candidate),
outside 43 (10 controls; 28 singles outside the candidate library: eight
inclusions over four sites, stiff and soft, six gradients over three
directions, six strain-stiffening laws (Yeoh, Gent, Demiray), four
Mooney-Rivlin laws, four sliding bases, weak and strong; five pairs of two
families; no effect of the library); every lambda/mu of each set is in
[2, 10].

Run: /usr/bin/python3 tests/truth/test_benchmark_sets.py SOURCE_DIR
"""
import sys
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(sys.argv[1]) / "bench" / "truth"))
import benchmark_set  # noqa: E402

SIZES = {"main": (42, 14), "validation": (12, 2), "holdout": (12, 4), "confirm": (12, 4), "effect": (16, 4),
         "refine": (15, 4), "tether": (15, 4), "skinvar": (14, 2),
         "glandform": (14, 3), "outside": (43, 10)}


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
    outside()
    shared = [n for n, k in names.items() if k > 1] + [s for s, k in seeds.items() if k > 1]
    assert not shared, f"shared between sets: {shared}"
    print("benchmark sets: OK")


def outside():
    """The outside set: only effects outside the library, each with its
    family as the hidden physics; >= 30 effect recordings, >= 4 pairs of
    two families, weak and strong."""
    from forms_truth import EFFECTS, OUTSIDE_LIBRARY, physics_of
    outside_names = {m.NAME for m in OUTSIDE_LIBRARY}
    recs = benchmark_set.recordings("outside")
    assert all(r["name"].startswith("out_") for r in recs), [r["name"] for r in recs]
    effects = [e for r in recs for e in r["effects"]]
    assert {n for n, _ in effects} == outside_names, {n for n, _ in effects}
    assert all(EFFECTS[n].CANDIDATE is None for n, _ in effects)
    singles = Counter((r["effects"][0][0], r["strength_class"]) for r in recs if len(r["effects"]) == 1)
    assert singles == {("stiff_inclusion", "weak"): 4, ("stiff_inclusion", "strong"): 4,
                       ("stiffness_gradient", "weak"): 3, ("stiffness_gradient", "strong"): 3,
                       ("strain_stiffening", "weak"): 3, ("strain_stiffening", "strong"): 3,
                       ("mooney_rivlin", "weak"): 4,
                       ("sliding_base", "weak"): 2, ("sliding_base", "strong"): 2}, singles
    pairs = [r for r in recs if r["strength_class"] == "pair"]
    assert len(pairs) == 5 and all(len(r["effects"]) == 2 for r in pairs), pairs
    assert all(len({physics_of(n) for n, _ in r["effects"]}) == 2 for r in pairs), "a pair within one family"
    assert sum(1 for r in recs if r["effects"]) >= 30
    sites = Counter((p["site"], p["kind"]) for n, p in effects if n == "stiff_inclusion")
    assert all(sites[(s, k)] >= 1 for s in ("lateral_upper", "lower_pole", "medial", "deep")
               for k in ("stiff", "soft")), sites
    laws = Counter(p["law"] for n, p in effects if n == "strain_stiffening")
    assert set(laws) == {"yeoh", "gent", "demiray"}, laws
    directions = Counter(p["direction"] for n, p in effects if n == "stiffness_gradient")
    assert set(directions) == {"base_apex", "lateral_medial", "upper_lower"}, directions
    # the other sets hold only effects of the library
    for which in benchmark_set.SETS:
        if which != "outside":
            assert not any(n in outside_names for r in benchmark_set.recordings(which) for n, _ in r["effects"]), which


if __name__ == "__main__":
    main()
