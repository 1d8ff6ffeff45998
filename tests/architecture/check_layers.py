"""The layer rules of docs/ARCHITECTURE.md, checked on the sources.

Fails (exit 1) when
- a file includes a project header of a layer its own layer may not use, or
- the project's units (foo.hpp + foo.cpp) include each other in a cycle.
Usage: check_layers.py SOURCE_ROOT
"""
import os
import re
import sys

# Folder -> layer, and the layers each layer may use directly (the uses are
# closed transitively below). Mirrors the link dependencies in CMakeLists.txt.
LAYERS = {
    "src/core": "core", "src/forms": "forms", "src/case": "case", "src/mesh": "mesh", "src/scan": "scan",
    "src/model": "model", "src/solver": "solver", "src/io": "io", "verification": "verification",
    "src/jobs": "jobs", "calibrate": "calibrate", "src/app": "app", "src/cli": "cli", "tests": "tests",
}
USES = {
    "core": [], "forms": [], "case": ["core", "forms"], "mesh": ["case"], "scan": ["mesh"], "model": ["mesh"],
    "solver": ["model"], "io": ["model"], "verification": ["model"],
    "jobs": ["solver", "io", "verification", "scan"], "calibrate": ["solver", "io"],
    "app": ["jobs", "calibrate"], "cli": ["app", "jobs", "calibrate"], "tests": ["app", "jobs", "calibrate"],
}
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def allowed(layer):
    """The layer itself and every layer it reaches through USES."""
    seen, todo = {layer}, list(USES[layer])
    while todo:
        l = todo.pop()
        if l not in seen:
            seen.add(l)
            todo += USES[l]
    return seen


def layer_of(path):
    best = None
    for folder, layer in LAYERS.items():
        if path == folder or path.startswith(folder + "/"):
            if best is None or len(folder) > len(best[0]):
                best = (folder, layer)
    return best[1] if best else None


def sources(root):
    for folder in LAYERS:
        for dirpath, _, files in os.walk(os.path.join(root, folder)):
            for f in files:
                if f.endswith((".hpp", ".cpp")):
                    yield os.path.relpath(os.path.join(dirpath, f), root)


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


def main(root):
    files = sorted(sources(root))
    by_name = {}
    for f in files:
        by_name.setdefault(os.path.basename(f), []).append(f)
    errors = [f"header name {n} is not unique: {', '.join(p)}" for n, p in by_name.items()
              if n.endswith(".hpp") and len(p) > 1]
    units = {}
    for f in files:
        layer = layer_of(f)
        unit = os.path.splitext(f)[0]
        for inc in INCLUDE.findall(open(os.path.join(root, f)).read()):
            target = by_name.get(os.path.basename(inc))
            if not target:
                continue  # generated or third-party
            t = target[0]
            if layer_of(t) not in allowed(layer):
                errors.append(f"{f} (layer {layer}) includes {t} (layer {layer_of(t)})")
            if os.path.splitext(t)[0] != unit and layer != "tests":
                units.setdefault(unit, set()).add(os.path.splitext(t)[0])
    cycle = find_cycle(units)
    if cycle:
        errors.append("include cycle: " + " -> ".join(cycle))
    for e in errors:
        print("layer check:", e)
    print(f"layer check: {len(files)} files, {sum(len(v) for v in units.values())} unit dependencies, "
          f"{len(errors)} problem(s)")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
