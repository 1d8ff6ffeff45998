# SPDX-License-Identifier: LGPL-3.0-or-later
"""The layer rules of docs/ARCHITECTURE.md, checked on the sources.

Each folder that holds C++ sources under src/, calibrate/ (each of its
subfolders is a folder of its own), diagnose/, verification/ and tests/ is
one node of the folder-level include graph: an edge A -> B when a file in A
includes a header in B. Fails (exit 1) when
- a folder holds C++ sources but has no entry in LAYERS,
- a file includes a header of a folder its own folder may not use (a
  higher layer, or one beside it),
- folders include each other in a cycle,
- the project's units (foo.hpp + foo.cpp) include each other in a cycle,
- a header name is not unique (the includes name headers without a folder).
Usage: check_layers.py SOURCE_ROOT [--graph]   (--graph: print the folder graph)
       check_layers.py --selftest               (the checks fail on hand-made trees)
"""
import os
import re
import sys
import tempfile

# Folder -> the folders its files may include directly (closed transitively
# below). Mirrors the link dependencies in CMakeLists.txt; the subfolders of
# calibrate/ share one library, breastsim_calibrate, so only this table
# orders them.
LAYERS = {
    "src/core": [], "src/forms": [], "src/case": ["src/core", "src/forms"], "src/mesh": ["src/case"],
    "src/scan": ["src/mesh"], "src/model": ["src/mesh"], "src/solver": ["src/model"], "src/io": ["src/model"],
    "verification": ["src/model"], "src/jobs": ["src/solver", "src/io", "verification", "src/scan"],
    "calibrate/inputs": ["src/solver", "src/io"], "calibrate/plots": ["src/solver", "src/io"],
    "calibrate/forward": ["calibrate/inputs"], "calibrate/fit": ["calibrate/forward", "calibrate/plots"],
    "diagnose": ["calibrate/fit"],
    "src/clinic": ["src/jobs", "calibrate/fit"],
    "src/app": ["src/jobs", "diagnose", "src/clinic"], "src/cli": ["src/app", "src/jobs", "diagnose", "src/clinic"],
    "tests": ["src/app", "src/jobs", "diagnose", "src/clinic"],
}
ROOTS = ("src", "calibrate", "diagnose", "verification", "tests")
SKIP = {"node_modules"}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def allowed(folder, layers):
    """The folder itself and every folder it reaches through `layers`."""
    seen, todo = {folder}, list(layers.get(folder, ()))
    while todo:
        f = todo.pop()
        if f not in seen:
            seen.add(f)
            todo += layers.get(f, ())
    return seen


def sources(root, roots):
    for top in roots:
        for dirpath, dirs, files in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(d for d in dirs if d not in SKIP)
            for f in sorted(files):
                if f.endswith((".hpp", ".cpp")):
                    yield os.path.relpath(os.path.join(dirpath, f), root).replace(os.sep, "/")


def find_cycle(graph):
    """One cycle of the directed graph (a list of nodes), or None."""
    state, stack = {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(graph.get(n, ())):
            if state.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if m not in state:
                c = visit(m)
                if c:
                    return c
        stack.pop()
        state[n] = 2
        return None

    for n in sorted(graph):
        if n not in state:
            c = visit(n)
            if c:
                return c
    return None


def check(root, layers=LAYERS, roots=ROOTS, top="tests"):
    """(problems, folder graph, number of files) of the tree at `root`.
    `top`: the folder of the tests, left out of the unit graph."""
    files = list(sources(root, roots))
    by_name = {}
    for f in files:
        by_name.setdefault(os.path.basename(f), []).append(f)
    errors = [f"header name {n} is not unique: {', '.join(p)}" for n, p in sorted(by_name.items())
              if n.endswith(".hpp") and len(p) > 1]
    cycle = find_cycle(layers)
    if cycle:
        errors.append("the layer table itself has a cycle: " + " -> ".join(cycle))
    folders, units = {}, {}
    for f in files:
        folder, unit = os.path.dirname(f), os.path.splitext(f)[0]
        if folder not in layers:
            if folder not in folders:
                errors.append(f"folder {folder} ({f}, ...) has no layer (tests/architecture/check_layers.py LAYERS)")
            folders.setdefault(folder, set())
            continue
        folders.setdefault(folder, set())
        with open(os.path.join(root, f), encoding="utf-8") as src:
            includes = INCLUDE.findall(src.read())
        for inc in includes:
            target = by_name.get(os.path.basename(inc))
            if not target:
                continue  # generated or third-party
            t = target[0]
            t_folder = os.path.dirname(t)
            if t_folder not in allowed(folder, layers):
                errors.append(f"{f} (folder {folder}) includes {t} (folder {t_folder}): not a layer "
                              f"{folder} may use")
            if t_folder != folder:
                folders[folder].add(t_folder)
            if os.path.splitext(t)[0] != unit and folder != top:
                units.setdefault(unit, set()).add(os.path.splitext(t)[0])
    cycle = find_cycle(folders)
    if cycle:
        errors.append("folder include cycle: " + " -> ".join(cycle))
    cycle = find_cycle(units)
    if cycle:
        errors.append("include cycle: " + " -> ".join(cycle))
    return errors, folders, len(files)


def main(root, show_graph=False):
    errors, folders, n = check(root)
    if show_graph:
        for folder in sorted(folders):
            print(f"{folder} -> {', '.join(sorted(folders[folder])) or '-'}")
    for e in errors:
        print("layer check:", e)
    print(f"layer check: {n} files in {len(folders)} folders, "
          f"{sum(len(v) for v in folders.values())} folder dependencies, {len(errors)} problem(s)")
    return 1 if errors else 0


def selftest():
    """The checks on small hand-made trees: a clean one passes, and each
    broken rule is reported."""
    def problems(files, layers):
        with tempfile.TemporaryDirectory(prefix="check_layers_") as root:
            for path, includes in files.items():
                os.makedirs(os.path.join(root, os.path.dirname(path)), exist_ok=True)
                with open(os.path.join(root, path), "w") as f:
                    f.write("".join(f'#include "{i}"\n' for i in includes) + "#include <vector>\n")
            return check(root, layers, roots=("lo", "hi", "side", "tests"))[0]

    layers = {"lo": [], "hi": ["lo"], "tests": ["hi"]}
    clean = {"lo/a.hpp": [], "lo/a.cpp": ["a.hpp"], "hi/b.hpp": ["a.hpp"], "hi/b.cpp": ["b.hpp"],
             "tests/test_b.cpp": ["b.hpp", "a.hpp"]}
    cases = [
        ("clean tree", clean, layers, []),
        ("include of a higher layer", {**clean, "lo/c.cpp": ["b.hpp"]}, layers,
         ["lo/c.cpp (folder lo) includes hi/b.hpp (folder hi)", "folder include cycle: hi -> lo -> hi"]),
        # A table that lets two folders use each other: only the cycle check stops them.
        ("folder cycle", {**clean, "lo/c.cpp": ["b.hpp"]}, {"lo": ["hi"], "hi": ["lo"], "tests": ["hi"]},
         ["the layer table itself has a cycle: hi -> lo -> hi", "folder include cycle: hi -> lo -> hi"]),
        ("unit cycle", {**clean, "lo/d.hpp": ["e.hpp"], "lo/e.cpp": ["d.hpp"], "lo/e.hpp": []}, layers,
         ["include cycle: lo/d -> lo/e -> lo/d"]),
        ("folder without a layer", {**clean, "side/s.cpp": ["a.hpp"]}, layers,
         ["folder side (side/s.cpp, ...) has no layer"]),
        ("header name twice", {**clean, "hi/a.hpp": []}, layers, ["header name a.hpp is not unique"]),
    ]
    failed = 0
    for name, files, table, expected in cases:
        got = problems(files, table)
        ok = len(got) == len(expected) and all(any(g.startswith(e) for g in got) for e in expected)
        print(f"selftest {name}: {'ok' if ok else 'FAILED'}" + ("" if ok else f" (got {got})"))
        failed += not ok
    return 1 if failed else 0


if __name__ == "__main__":
    args = sys.argv[1:]
    if args == ["--selftest"]:
        sys.exit(selftest())
    sys.exit(main(next((a for a in args if not a.startswith("--")), "."), "--graph" in args))
