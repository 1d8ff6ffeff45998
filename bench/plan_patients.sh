#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# `breastsim plan` on the five synthetic patients of bench/clinic/patients.json:
# per patient and breast, whether every target is met, the result against
# each target and the wall time (docs/CLINIC.md, "Figures").
# Usage: bash bench/plan_patients.sh BIN [OUT]   (about 10 minutes on 2 cores)
set -eu
BIN="$1"; OUT="${2:-$(mktemp -d)}"
HERE="$(cd "$(dirname "$0")" && pwd)"
mkdir -p "$OUT"
/usr/bin/python3 - "$BIN" "$OUT" "$HERE/clinic/patients.json" <<'PY'
import json, os, subprocess, sys, time
bin_, out, spec = sys.argv[1:4]
rows = []
for p in json.load(open(spec))["patients"]:
    doc = {"format": "breastsim-patient/1", "id": p["id"], "units": p["units"],
           "left": p["left"], "right": p["right"]}
    pf = os.path.join(out, p["id"] + ".json")
    json.dump(doc, open(pf, "w"))
    args = [bin_, "-q", "plan", pf, "--out", os.path.join(out, p["id"])]
    for side, t in p["targets"].items():
        args += [a for k, v in t.items() for a in ("--target", f"{side}.{k}={v}")]
    t0 = time.time()
    r = subprocess.run(args, capture_output=True, text=True)
    wall = time.time() - t0
    if r.returncode not in (0, 4):
        sys.exit(f"{p['id']}: exit {r.returncode}\n{r.stderr}")
    plan = json.load(open(os.path.join(out, p["id"], "plan.json")))
    for s in plan["sides"]:
        post, surg = s["plan"].get("post_standing", {}), s["plan"].get("surgical", {})
        got = {"sn_n_mm": post.get("sn_n_mm"), "n_imf_mm": post.get("n_imf_mm"),
               "resection_g": surg.get("resection_g"), "lower_pole_share": post.get("lower_pole_share")}
        rows.append({"patient": p["id"], "side": s["side"], "met": s["met"], "targets": s["targets"],
                     "result": {k: got[k] for k in s["targets"]}, "unmet": s["unmet"],
                     "searched": len(s["searched"]), "wall_s": wall})
        fmt = ", ".join(f"{k} {got[k]:.1f} (target {v})" for k, v in s["targets"].items())
        print(f"{p['id']} {s['side']:5}: {'met' if s['met'] else 'NOT met'}: {fmt}; {len(s['searched'])} plans; patient {wall:.0f} s")
json.dump(rows, open(os.path.join(out, "plan_patients.json"), "w"), indent=1)
met = sum(r["met"] for r in rows)
print(f"met: {met} of {len(rows)} breasts; results in {out}")
PY
