#!/usr/bin/env python3
"""Coverage of the reference q by the 95 % interval under each rule for the
model-form part of its standard error, from one benchmark run's
diagnosis.json files (their parts: se_log_statistical, se_log_numerical,
se_log_posture_jackknife, se_log_patch_jackknife; docs/DIAGNOSE.md step 9).

    python3 bench/truth/coverage_by_rule.py [--manifest M] [--out RESULTS]
    python3 bench/truth/coverage_by_rule.py --selftest

The interval of rule R is q_hat exp(+-1.96 SE_R) with
    SE_R = sqrt(se_stat^2 + se_num^2 + se_form_R^2),
    se_form_R = 0 (none), the posture jackknife, the patch jackknife, or the
    larger of the two (the rule diagnose uses);
the reference q is the pseudo-true value where pseudo_true.py computed one,
else the manifest's equivalent (run_diagnose.py). Only the standard library.
"""
import argparse
import json
import math
import tempfile
from pathlib import Path

from run_diagnose import HERE, pseudo_true_recordings, read_pseudo_true

RULES = {
    "none": lambda post, patch: 0.0,
    "posture jackknife": lambda post, patch: post,
    "patch jackknife": lambda post, patch: patch,
    "larger of the two": lambda post, patch: max(post, patch),
}


def parts(dia, name):
    """(q_hat, se_stat, se_num, se_posture, se_patch) of parameter `name`."""
    names = [p["name"] for p in dia["final"]["parameters"]]
    i = names.index(name)
    pick = lambda key: (dia.get(key) or [0.0] * len(names))[i]
    return (dia["final"]["parameters"][i]["value"], pick("se_log_statistical"), pick("se_log_numerical"),
            pick("se_log_posture_jackknife"), pick("se_log_patch_jackknife"))


def read_pseudo_material(manifest_dir):
    """{recording: {"mu": mu*, "lambda": lambda*}} of pseudo_true.json
    (definition 3: fitted with the candidates), {} if absent."""
    out = {}
    for name, entry in pseudo_true_recordings(manifest_dir).items():
        for cand in entry.get("candidates", {}).values():
            if "material" in cand:
                out[name] = cand["material"]
    return out


def cases(manifest, out, pseudo, tissue, material=None):
    """(recording, parameter, reference, kind, parts) per correct discovery's
    q, or (tissue) per recording's mu and lambda: the truth's for a control
    (in the family), for an effect recording mu*, lambda* fitted with the
    candidates' forms (`material`) where known, else the truth's."""
    material = material or {}
    for name, entry in sorted(manifest["recordings"].items()):
        path = out / name / "diagnosis" / "diagnosis.json"
        if not path.exists():
            continue
        dia = json.loads(path.read_text())
        if tissue:
            best = material.get(name) if entry["effects"] else None
            for key in ("mu", "lambda"):
                ref, kind = (best[key], "pseudo-true") if best else (entry["material"][key], "truth")
                yield name, key, ref, kind, parts(dia, key)
            continue
        for eff in entry["effects"]:
            if eff["candidate"] not in dia.get("discovered", []):
                continue
            q = eff["q_equivalent"]
            ref = pseudo.get(name, {}).get(eff["candidate"])
            kind = ("equivalent" if ref is None else
                    "pseudo-true" if name in material else "pseudo-true, mu lambda fixed")
            yield (name, eff["candidate"], ref if ref is not None else q["value"], kind,
                   parts(dia, q["parameter"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--manifest", default=str(HERE / "manifest.json"))
    ap.add_argument("--out", default=str(HERE / "results"))
    ap.add_argument("--selftest", action="store_true", help="check the rules on a hand-made result")
    a = ap.parse_args()
    if a.selftest:
        return selftest()
    manifest_path = Path(a.manifest)
    manifest = json.loads(manifest_path.read_text())
    pseudo = read_pseudo_true(manifest_path.parent)
    material = read_pseudo_material(manifest_path.parent)
    for tissue in (False, True):
        table(list(cases(manifest, Path(a.out), pseudo, tissue, material)),
              "tissue mu, lambda" if tissue else
              "candidate q of the correct discoveries")
    return 0


def count_inside(rows):
    """{rule: references inside its interval}."""
    return {rule: sum(abs(math.log(ref / q)) <= 1.96 * math.sqrt(st ** 2 + nu ** 2 + form(po, pa) ** 2)
                      for _, _, ref, _, (q, st, nu, po, pa) in rows)
            for rule, form in RULES.items()}


def table(rows, what):
    print(f"\n### {what}\n")
    print("| recording | parameter | reference | fitted | ln(ref/fitted) | se stat | se num | "
          "se posture | se patch |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, cand, ref, kind, (q, st, nu, po, pa) in rows:
        print(f"| {name} | {cand} | {ref:.3g} ({kind}) | {q:.3g} | {math.log(ref / q):+.3f} | {st:.3f} | "
              f"{nu:.3f} | {po:.3f} | {pa:.3f} |")
    best = [r for r in rows if r[3] in ("pseudo-true", "truth")]
    print(f"\n| rule for the model-form part | reference inside the 95 % interval (of {len(rows)}) | "
          f"of them pseudo-true (mu, lambda fitted) or truth (of {len(best)}) |")
    print("|---|---|---|")
    for (rule, inside), inside_best in zip(count_inside(rows).items(), count_inside(best).values()):
        print(f"| {rule} | {inside} | {inside_best} |")


def selftest():
    """q = 2 fitted, reference 2 exp(0.3) (ln ratio 0.3), se stat 0.1, num 0.05:
    none covers (1.96 x 0.112 = 0.22), the posture jackknife 0.1 does not
    (0.29), the patch jackknife 0.2 does (0.47), hence the larger of the two."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp)
        manifest = {"recordings": {"r": {"effects": [{"candidate": "skin",
                                                        "q_equivalent": {"parameter": "skin.mu", "value": 2 * math.exp(0.3)}}],
                                         "material": {"mu": 500.0, "lambda": 1000.0}}}}
        dia = {"discovered": ["skin"],
               "final": {"parameters": [{"name": "mu", "value": 500.0}, {"name": "lambda", "value": 1000.0},
                                        {"name": "skin.mu", "value": 2.0}]},
               "se_log_statistical": [0.01, 0.01, 0.1], "se_log_numerical": [0, 0, 0.05],
               "se_log_posture_jackknife": [0, 0, 0.1], "se_log_patch_jackknife": [0, 0, 0.2]}
        (out / "r" / "diagnosis").mkdir(parents=True)
        (out / "r" / "diagnosis" / "diagnosis.json").write_text(json.dumps(dia))
        got = count_inside(list(cases(manifest, out, {}, False)))
        want = {"none": 0, "posture jackknife": 0, "patch jackknife": 1, "larger of the two": 1}
        assert got == want, got
        tissue = count_inside(list(cases(manifest, out, {}, True)))
        assert tissue["none"] == 2, tissue
        # mu* = 520 fitted with the candidate: ln(520/500) = 0.039 > 1.96 x 0.01
        best = {"r": {"mu": 520.0, "lambda": 1000.0}}
        tissue = count_inside(list(cases(manifest, out, {}, True, best)))
        assert tissue["none"] == 1, tissue
    print("coverage_by_rule selftest: OK")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
