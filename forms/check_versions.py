# SPDX-License-Identifier: LGPL-3.0-or-later
"""Configure-time check of the form compiler stack (prints versions)."""
import sys
try:
    import ffcx
    import ufl
    import basix
except ImportError as e:
    sys.exit(f"breastsim: cannot import the form compiler stack under {sys.executable}: {e}. "
             "Install Debian's python3-ffcx (0.5) and python3-basix.")
want = {"ffcx": "0.5", "ufl": "2022.2", "basix": "0.5"}
got = {"ffcx": ffcx.__version__, "ufl": ufl.__version__, "basix": basix.__version__}
bad = [f"{k} {got[k]} (expected {want[k]}.x)" for k in want if not got[k].startswith(want[k])]
if bad:
    sys.exit("breastsim: unexpected form compiler versions: " + ", ".join(bad))
print(";".join(f"{k}={got[k]}" for k in want))
