#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim plan` on the five synthetic patients of bench/clinic/patients.json
# (docs/CLINIC.md, "Figures"). Per breast: the hidden incision is evaluated
# (`plan --incision`) and its post-operative SN-N, N-IMF (to 0.1 cm) and
# weight (to 1 g) become the targets of a search (`plan --target`), which
# must meet them: reachable by construction. Then an unreachable target
# (a 2000 g resection, more than any of these breasts weighs) must exit 4
# naming it with the weights in reach. Prints per breast the targets,
# the result and the wall time; writes OUT/plan_patients.json.
# Usage: bash bench/plan_patients.sh BIN [OUT]   (about 15 minutes on 2 cores)
set -eu
BIN="$1"; OUT="${2:-$(mktemp -d)}"
HERE="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$OUT"
/usr/bin/python3 - "$BIN" "$OUT" "$HERE/clinic/patients.json" <<'PY'
import json, os, subprocess, sys, time
bin_, out, spec = sys.argv[1:4]

def plan(pf, name, args):
    t0 = time.time()
    r = subprocess.run([bin_, "-q", "plan", pf, "--out", os.path.join(out, name)] + args, capture_output=True, text=True)
    if r.returncode not in (0, 4):
        sys.exit(f"{name}: exit {r.returncode}\n{r.stderr}")
    return r, json.load(open(os.path.join(out, name, "plan.json"))), time.time() - t0

rows = []
for p in json.load(open(spec))["patients"]:
    doc = {k: p[k] for k in ("id", "units", "left", "right")}
    doc["format"] = "breastsim-patient/1"
    pf = os.path.join(out, p["id"] + ".json")
    json.dump(doc, open(pf, "w"))
    for side, inc in p["hidden"].items():
        _, hidden, _ = plan(pf, f"{p['id']}-{side}-hidden", ["--incision", f"{side}." + ",".join(map(str, inc))])
        h = hidden["sides"][0]["plan"]
        if not h["ok"]:
            sys.exit(f"{p['id']} {side}: the hidden incision is not operable: {h['error']}")
        t = {"sn_n": round(h["post_standing"]["sn_n_mm"] / 10, 1), "n_imf": round(h["post_standing"]["n_imf_mm"] / 10, 1),
             "grams": round(h["surgical"]["resection_g"])}
        args = ["--target", f"{side}.sn_n={t['sn_n']}cm", "--target", f"{side}.n_imf={t['n_imf']}cm",
                "--target", f"{side}.grams={t['grams']}"]
        r, found, wall = plan(pf, f"{p['id']}-{side}", args)
        s = found["sides"][0]
        post, surg = s["plan"].get("post_standing", {}), s["plan"].get("surgical", {})
        got = {"sn_n": post.get("sn_n_mm", 0) / 10, "n_imf": post.get("n_imf_mm", 0) / 10, "grams": surg.get("resection_g", 0)}
        r4, _, _ = plan(pf, f"{p['id']}-{side}-unreachable", ["--target", f"{side}.grams=2000"])
        refused = r4.returncode == 4 and "a resection of 2000 g is out of reach" in r4.stderr
        rows.append({"patient": p["id"], "side": side, "hidden_incision": inc, "targets": t, "result": got,
                     "met": s["met"], "unmet": s["unmet"], "searched": len(s["searched"]), "wall_s": wall,
                     "unreachable_refused": refused})
        print(f"{p['id']} {side:5}: {'met' if s['met'] else 'NOT met'}: SN-N {got['sn_n']:.1f} (target {t['sn_n']}) cm, "
              f"N-IMF {got['n_imf']:.1f} (target {t['n_imf']}) cm, {got['grams']:.0f} (target {t['grams']}) g; "
              f"{len(s['searched'])} surgeries, {wall:.0f} s; 2000 g refused: {refused}", flush=True)
json.dump(rows, open(os.path.join(out, "plan_patients.json"), "w"), indent=1)
met = sum(r["met"] for r in rows)
patients = len({r["patient"] for r in rows if all(q["met"] for q in rows if q["patient"] == r["patient"])})
print(f"met: {met} of {len(rows)} breasts, {patients} of 5 patients; unreachable refused: "
      f"{sum(r['unreachable_refused'] for r in rows)} of {len(rows)}; results in {out}")
PY
