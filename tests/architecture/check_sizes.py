# SPDX-License-Identifier: LGPL-3.0-or-later
"""Size rules of docs/ARCHITECTURE.md: no C++ file over MAX_FILE lines and no
function body over MAX_FUNCTION lines (from the line of its opening brace at
the start of a line to its closing brace, the layout clang-format gives).

Usage: check_sizes.py SOURCE_ROOT [--list]   (exit 1 on a violation; --list
only prints them and exits 0)
"""
import os
import re
import sys

MAX_FILE, MAX_FUNCTION = 500, 80
FOLDERS = ("src", "calibrate", "diagnose", "verification")
SIGNATURE = re.compile(r"^[A-Za-z_][\w:<>,\s\*&~\[\]]*\([^;]*$")


def functions(lines):
    """(name line, length) of every top-level or namespace-level function body."""
    depth, out, start, name = 0, [], None, None
    for i, line in enumerate(lines):
        stripped = line.strip()
        if start is None and line.startswith("{") and i > 0:
            # The signature ends on one of the lines above the brace.
            head = next((lines[k] for k in range(i - 1, max(i - 6, -1), -1) if lines[k].strip()), "")
            if not re.match(r"^\s*(namespace|struct|class|enum|union|extern)\b", head) and \
                    not head.rstrip().endswith(("=", ",")) and "(" in "".join(lines[max(i - 6, 0):i]):
                start, name, depth = i, head.strip(), 0
        if start is not None:
            depth += stripped.count("{") - stripped.count("}")
            if depth == 0:
                out.append((start, name, i - start + 1))
                start = None
    return out


def main(root, list_only):
    problems = []
    for folder in FOLDERS:
        for dirpath, _, files in os.walk(os.path.join(root, folder)):
            for f in sorted(files):
                if not f.endswith((".cpp", ".hpp")):
                    continue
                path = os.path.join(dirpath, f)
                rel = os.path.relpath(path, root)
                lines = open(path).read().split("\n")
                if len(lines) > MAX_FILE:
                    problems.append(f"{rel}: {len(lines)} lines (max {MAX_FILE})")
                for start, name, n in functions(lines):
                    if n > MAX_FUNCTION:
                        problems.append(f"{rel}:{start + 1}: function of {n} lines (max {MAX_FUNCTION}): {name[:70]}")
    for p in problems:
        print("size check:", p)
    print(f"size check: {len(problems)} problem(s)")
    return 0 if list_only or not problems else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else ".", "--list" in sys.argv))
