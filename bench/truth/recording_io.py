# SPDX-License-Identifier: LGPL-3.0-or-later
"""Writing recordings in breastsim's format (breastsim-recording/1, the keys
read by calibrate/inputs/recording.cpp) and the benchmark manifest.

The checks below mirror calibrate/inputs/recording.cpp, so that a recording this
generator writes is one `breastsim diagnose` accepts.
"""
import json
import math
import os
from pathlib import Path

FORMAT = "breastsim-recording/1"
TOP_KEYS = {"format", "noise_sigma", "known", "postures", "truth", "units", "comment", "written_by"}
POSTURE_KEYS = {"name", "theta_deg", "points", "landmarks"}
DIGITS = 5   # coordinates rounded to 1e-5 m (0.01 mm, far below the 0.5 mm noise)


def _finite(x, key, lo, hi):
    if not isinstance(x, (int, float)) or not math.isfinite(x) or not (lo <= x <= hi):
        raise ValueError(f"recording: key '{key}' = {x!r} must be a finite number in [{lo}, {hi}]")


def check_recording(rec):
    """The rules of calibrate/inputs/recording.cpp: allowed keys, ranges, >= 10
    points per posture, x >= -5 sigma, unique posture names."""
    extra = set(rec) - TOP_KEYS
    if extra:
        raise ValueError(f"recording: keys {sorted(extra)} are not allowed")
    if rec.get("format") != FORMAT or rec.get("units", "m") != "m":
        raise ValueError("recording: format / units")
    sigma = rec["noise_sigma"]
    _finite(sigma, "noise_sigma", 1e-7, 0.02)
    known_ranges = {"R": (0.02, 0.2), "H": (0.01, 0.2), "rho": (500, 2000)}
    for k, v in rec.get("known", {}).items():
        _finite(v, f"known.{k}", *known_ranges[k])
    names = set()
    if not rec["postures"]:
        raise ValueError("recording: no postures")
    for i, p in enumerate(rec["postures"]):
        if set(p) - POSTURE_KEYS:
            raise ValueError(f"recording: postures[{i}] has keys {sorted(set(p) - POSTURE_KEYS)}")
        if not p["name"] or p["name"] in names:
            raise ValueError(f"recording: postures[{i}].name empty or repeated")
        names.add(p["name"])
        _finite(p["theta_deg"], f"postures[{i}].theta_deg", -180, 180)
        if len(p["points"]) < 10:
            raise ValueError(f"recording: postures[{i}] has fewer than 10 points")
        for q in p["points"] + [p.get("landmarks", {}).get("nipple", [0, 0, 0])]:
            if len(q) != 3:
                raise ValueError(f"recording: postures[{i}]: a point is not [x, y, z]")
            for c in q:
                _finite(c, f"postures[{i}].points", -1.0, 1.0)
            if q[0] < -5 * sigma:
                raise ValueError(f"recording: postures[{i}]: x = {q[0]} < -5 sigma")


def rounded(points):
    return [[round(float(c), DIGITS) for c in q] for q in points]


def make_recording(name, noise_sigma, known, postures):
    """postures: list of {name, theta_deg, points (n, 3), nipple (3,)}."""
    rec = {"format": FORMAT, "units": "m", "written_by": "bench/truth/generate.py",
           "comment": "independent truth (bench/truth/README.md); hidden effects in "
                      "bench/truth/manifest.json",
           "noise_sigma": noise_sigma, "known": known, "postures": []}
    for p in postures:
        rec["postures"].append({"name": p["name"], "theta_deg": p["theta_deg"],
                                "points": rounded(p["points"]),
                                "landmarks": {"nipple": rounded([p["nipple"]])[0]}})
    rec["truth"] = {"generator": "bench/truth/generate.py", "name": name,
                    "details": "bench/truth/manifest.json"}
    check_recording(rec)
    return rec


def write_json_atomic(path, obj, compact=False):
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp-{os.getpid()}")
    text = json.dumps(obj, separators=(",", ":")) if compact else json.dumps(obj, indent=1)
    tmp.write_text(text + "\n")
    os.replace(tmp, path)


def read_manifest(path):
    path = Path(path)
    if not path.exists():
        return None
    return json.loads(path.read_text())
