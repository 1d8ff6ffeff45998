#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Write index.html: a self-contained 3D page of a breastsim result folder.

The page inlines three.js (npm package `three`, installed into
src/viewer/web/node_modules by `.ci/setup`), its OrbitControls, the viewer
script web/viewer.js and the surface_<posture>.json data of the result folder
(and of a comparison folder), so it works offline from file:// and fetches
nothing.

Usage: page.py RESULT_DIR [--compare OTHER_DIR] [--out FILE]
Exit codes: 0 ok, 2 bad input, 4 three.js not installed.
"""
import argparse
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
WEB = os.path.join(HERE, "web")
THREE = os.path.join(WEB, "node_modules", "three")
POSTURE_ORDER = ["standing", "supine", "all_fours", "prone"]


class InputError(Exception):
    pass


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def script_safe(js):
    """Text that cannot end the inline <script> element early."""
    return js.replace("</script", "<\\/script").replace("<!--", "<\\!--")


def load_set(folder):
    if not os.path.isdir(folder):
        raise InputError(f"result folder '{folder}' does not exist")
    names = sorted(f for f in os.listdir(folder)
                   if f.startswith("surface_") and f.endswith(".json"))
    if not names:
        raise InputError(
            f"no surface_<posture>.json in '{folder}' (written by `breastsim simulate`)")
    surfaces = [json.loads(read(os.path.join(folder, n))) for n in names]
    surfaces.sort(key=lambda s: (POSTURE_ORDER.index(s["posture"])
                                 if s["posture"] in POSTURE_ORDER else 99, s["theta_deg"]))
    label = os.path.basename(os.path.normpath(os.path.abspath(folder)))
    return {"label": label, "surfaces": surfaces}


def make_page(result_dir, compare_dir=None):
    lib = os.path.join(THREE, "build", "three.min.js")
    orbit = os.path.join(THREE, "examples", "js", "controls", "OrbitControls.js")
    if not (os.path.isfile(lib) and os.path.isfile(orbit)):
        raise FileNotFoundError(
            f"three.js is not installed in {WEB}/node_modules: run `npm ci --prefix {WEB}` "
            f"(done by .ci/setup)")
    sets = [load_set(result_dir)] + ([load_set(compare_dir)] if compare_dir else [])
    if len(sets) == 2 and sets[0]["label"] == sets[1]["label"]:
        sets[1]["label"] += " (compare)"
    version = json.loads(read(os.path.join(THREE, "package.json")))["version"]
    title = " vs ".join(s["label"] for s in sets)
    data = json.dumps({"sets": sets}, separators=(",", ":"))
    parts = {
        "@TITLE@": title.replace("&", "&amp;").replace("<", "&lt;"),
        "@THREE_VERSION@": version,
        "@THREE@": script_safe(read(lib)),
        "@ORBIT@": script_safe(read(orbit)),
        "@DATA@": script_safe(data),
        "@APP@": script_safe(read(os.path.join(WEB, "viewer.js"))),
    }
    html = read(os.path.join(WEB, "viewer.html"))
    # One pass in template order, so inserted text is never searched again.
    out, pos = [], 0
    while True:
        hits = [(html.find(k, pos), k) for k in parts if html.find(k, pos) >= 0]
        if not hits:
            break
        i, k = min(hits)
        out += [html[pos:i], parts[k]]
        pos = i + len(k)
    out.append(html[pos:])
    return "".join(out)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("result_dir")
    ap.add_argument("--compare", metavar="OTHER_DIR")
    ap.add_argument("--out", help="page to write (default RESULT_DIR/index.html)")
    a = ap.parse_args(argv)
    try:
        html = make_page(a.result_dir, a.compare)
    except FileNotFoundError as e:
        sys.stderr.write(f"breastsim page: {e}\n")
        return 4
    except (InputError, KeyError, ValueError) as e:
        sys.stderr.write(f"breastsim page: {e}\n")
        return 2
    out = a.out or os.path.join(a.result_dir, "index.html")
    with open(out, "w", encoding="utf-8") as f:
        f.write(html)
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except OSError as e:  # a full disk, a folder that cannot be written: one line, no traceback
        sys.stderr.write(f"breastsim page: cannot write {e.filename or ''}: {e.strerror or e}\n")
        sys.exit(1)
