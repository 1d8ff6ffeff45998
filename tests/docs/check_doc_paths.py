#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Check the reference documents against the repository.

    python3 tests/docs/check_doc_paths.py SOURCE_DIR [BREASTSIM_BINARY]

Documents: README.md, CHANGELOG.md (if present) and docs/*.md.

1. Every repository path a document names exists: backticked spans, markdown
   links and images, and the words of code blocks (commands). A word is taken
   for a repository path when it contains '/' and its first part is an entry
   of the repository's top level (src/..., bench/..., docs/...), or when it is
   a bare file name with a source extension (.cpp, .hpp, .py, .sh, .js, .md,
   .cmake, .geo), which must then exist somewhere in the repository (files
   generated into the build tree are named with their build/ path). Markdown links
   are resolved from the document's folder. Ignored: URLs, absolute paths,
   paths with a `results`, `build` or `node_modules` part (made by a run, a
   build or `.ci/setup`), and placeholders (<...>, *, an
   upper-case part such as DIR or CASE that does not exist). A path that
   leaves the repository (../...) is an offender. `a/b.{hpp,cpp}` names both.
2. With the binary: the README's key table (from the line
   "| key | type | unit | default | allowed | meaning |" to the last table
   line after it) equals the output of `breastsim keys` line by line.
3. No document has a dated heading (a heading with a date such as
   2026-12-06) or an issue reference ("issue 48", "#48").

Exits 1 and lists the offenders (file:line: reason), 0 when all hold.
"""
import os
import re
import subprocess
import sys
from pathlib import Path

# Bare file names with these extensions are source files and must exist somewhere in the
# repository (output files such as summary.json, and case keys such as base.c, are not checked).
SOURCE_EXT = {".cpp", ".hpp", ".py", ".sh", ".js", ".md", ".cmake", ".geo"}
SKIP_DIRS = {".git", "build", "results", "node_modules", "__pycache__"}
KEYS_HEADER = "| key | type | unit | default | allowed | meaning |"
DATE = re.compile(r"\b(19|20)\d\d-\d\d-\d\d\b")
ISSUE = re.compile(r"\bissues?\s+#?\d+|(?<![\w&#/])#\d+\b", re.IGNORECASE)
HEADING = re.compile(r"^\s{0,3}#{1,6}\s")
FENCE = re.compile(r"^\s*(```|~~~)")
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
BACKTICK = re.compile(r"(`+)(.+?)\1")
WORD = re.compile(r"[A-Za-z0-9_.\-/{},<>*+~]+")


def documents(root):
    docs = [root / "README.md"]
    if (root / "CHANGELOG.md").exists():
        docs.append(root / "CHANGELOG.md")
    docs += sorted((root / "docs").glob("*.md"))
    return [d for d in docs if d.exists()]


def repo_files(root):
    """Base names of every file in the repository (for bare file names)."""
    names = set()
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if d not in SKIP_DIRS]
        names.update(filenames)
    return names


def expand_braces(word):
    m = re.search(r"\{([^{}]*)\}", word)
    if not m:
        return [word]
    out = []
    for alt in m.group(1).split(","):
        out += expand_braces(word[:m.start()] + alt + word[m.end():])
    return out


def is_placeholder(path):
    if any(c in path for c in "<>*$"):
        return True
    for part in path.split("/"):
        stem = part.split(".")[0]
        if len(stem) >= 2 and re.fullmatch(r"[A-Z][A-Z0-9_]*", stem):
            return True
    return False


def exists(path):
    """A file or folder, or a file stem named without its extension (src/mesh/incision)."""
    if path.exists():
        return True
    return path.suffix == "" and path.parent.is_dir() and any(path.parent.glob(path.name + ".*"))


def check_word(word, root, top, names):
    """None when fine or not a repository path, else the reason."""
    word = word.lstrip("(,;:'\"").rstrip(".,;:()'\"")
    if not word or "://" in word or word.startswith(("/", "~", "-")) or "=" in word:
        return None
    if ":" in word:  # forms/common.py:param
        word = word.split(":", 1)[0]
    reasons = []
    for w in expand_braces(word):
        w = w.rstrip("/")
        if not w or w in (".", ".."):
            continue
        parts = w.split("/")
        if "/" in w:
            if parts[0] == "..":
                if not (root / w).resolve().is_relative_to(root.resolve()):
                    reasons.append(f"`{w}` names a path outside the repository")
                elif not exists(root / w):
                    reasons.append(f"`{w}` does not exist")
                continue
            if parts[0] not in top or any(p in ("results", "build", "node_modules") for p in parts):
                continue
            if exists(root / w) or is_placeholder(w):
                continue
            reasons.append(f"`{w}` does not exist")
        else:
            ext = os.path.splitext(w)[1]
            if ext not in SOURCE_EXT or is_placeholder(w):
                continue
            if w not in names:
                reasons.append(f"`{w}` is not a file of the repository")
    return "; ".join(reasons) or None


def check_link(target, doc, root):
    target = target.split("#", 1)[0]
    if not target or re.match(r"^[a-z]+:", target) or target.startswith("/"):
        return None
    if is_placeholder(target):
        return None
    path = (doc.parent / target).resolve()
    if not path.is_relative_to(root.resolve()):
        return f"link `{target}` leaves the repository"
    if not path.exists():
        return f"link `{target}` does not exist"
    return None


def path_offenders(doc, root, top, names):
    out = []
    in_fence = False
    rel = doc.relative_to(root)
    for n, line in enumerate(doc.read_text(encoding="utf-8").splitlines(), 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        code = in_fence or (line.startswith("    ") and line.strip())
        words = []
        if code:
            words = WORD.findall(line)
        else:
            for m in LINK.finditer(line):
                reason = check_link(m.group(1), doc, root)
                if reason:
                    out.append(f"{rel}:{n}: {reason}")
            for m in BACKTICK.finditer(line):
                words += WORD.findall(m.group(2))
        for w in words:
            reason = check_word(w, root, top, names)
            if reason:
                out.append(f"{rel}:{n}: {reason}")
    return out


def history_offenders(doc, root):
    out = []
    rel = doc.relative_to(root)
    in_fence = False
    for n, line in enumerate(doc.read_text(encoding="utf-8").splitlines(), 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if in_fence:
            continue
        if HEADING.match(line) and DATE.search(line):
            out.append(f"{rel}:{n}: dated heading: {line.strip()}")
        for m in ISSUE.finditer(line):
            out.append(f"{rel}:{n}: issue reference '{m.group(0)}'")
    return out


def key_table_offenders(root, binary):
    readme = (root / "README.md").read_text(encoding="utf-8").splitlines()
    try:
        start = readme.index(KEYS_HEADER)
    except ValueError:
        return [f"README.md: no key table (a line '{KEYS_HEADER}')"]
    table = []
    for line in readme[start:]:
        if not line.startswith("|"):
            break
        table.append(line.rstrip())
    try:
        run = subprocess.run([binary, "keys"], capture_output=True, text=True, timeout=120)
    except OSError as e:
        return [f"{binary} keys: {e}"]
    if run.returncode != 0:
        return [f"{binary} keys: exit code {run.returncode}: {run.stderr.strip()}"]
    keys = [line.rstrip() for line in run.stdout.splitlines() if line.strip()]
    out = []
    for i in range(max(len(table), len(keys))):
        a = table[i] if i < len(table) else "(missing)"
        b = keys[i] if i < len(keys) else "(missing)"
        if a != b:
            out.append(f"README.md:{start + 1 + i}: key table differs from `breastsim keys`:\n"
                       f"    README: {a}\n    keys:   {b}")
    return out


def main(argv):
    if len(argv) not in (2, 3):
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    root = Path(argv[1]).resolve()
    top = {p.name for p in root.iterdir() if p.name not in (".git",)}
    names = repo_files(root)
    offenders = []
    for doc in documents(root):
        offenders += path_offenders(doc, root, top, names)
        offenders += history_offenders(doc, root)
    if len(argv) == 3:
        offenders += key_table_offenders(root, argv[2])
    if offenders:
        print(f"{len(offenders)} offender(s):")
        for o in offenders:
            print("  " + o)
        return 1
    print(f"docs: {len(documents(root))} documents checked"
          + (", key table equals `breastsim keys`" if len(argv) == 3 else "") + ": all hold")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
