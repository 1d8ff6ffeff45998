# SPDX-License-Identifier: LGPL-3.0-or-later
"""Configure-time helper: print the registered energy terms (forms/registry.py),
separated by ';' (a CMake list). Reads the registry without importing UFL."""
import ast
import os

path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "registry.py")
tree = ast.parse(open(path).read(), path)
terms = next(ast.literal_eval(node.value) for node in tree.body
             if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "TERMS" for t in node.targets))
for name in terms:
    if not os.path.exists(os.path.join(os.path.dirname(path), name + ".py")):
        raise SystemExit(f"forms/registry.py: term '{name}' has no file forms/{name}.py")
print(";".join(terms), end="")
