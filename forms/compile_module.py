# SPDX-License-Identifier: LGPL-3.0-or-later
"""Build-time driver: run ffcx on one module entry and write a Makefile
depfile naming every UFL source of this repository the entry loaded
(forms/*.py, verification/forms/*.py), so that a module is
recompiled exactly when one of its own UFL sources changes.

Usage: compile_module.py ENTRY.py OUTDIR DEPFILE
(PYTHONPATH must hold the entry's UFL folders; run under /usr/bin/python3 like ffcx.)
"""
import os
import sys

from ffcx.main import main

entry, outdir, depfile = sys.argv[1:4]
status = main([entry, "-o", outdir])
if status:
    sys.exit(status)

source_root = os.path.dirname(os.path.dirname(os.path.abspath(__file__))) + os.sep
loaded = sorted({os.path.abspath(m.__file__) for m in list(sys.modules.values())
                 if getattr(m, "__file__", None)
                 and os.path.abspath(m.__file__).startswith(source_root)})
base = os.path.splitext(os.path.basename(entry))[0]
target = os.path.join(os.path.abspath(outdir), base + ".c")
with open(depfile, "w") as f:
    f.write(target + ": " + " ".join(p.replace(" ", "\\ ") for p in loaded + [os.path.abspath(entry)]) + "\n")
