#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Checks on PNG pictures for the viewer tests (exit 1 with a message on failure).

  png_check.py size FILE WIDTH HEIGHT   the PNG header says WIDTH x HEIGHT, file non-empty
  png_check.py differ A B               the two pictures differ in at least 0.5 % of pixels
  png_check.py drawn FILE               at least 5 % of the pixels are not the background
"""
import struct
import sys


def header_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        sys.exit(f"{path}: not a PNG file")
    return struct.unpack(">II", head[16:24])


def pixels(path):
    import matplotlib.image as mpimg  # Debian python3-matplotlib (also renders them)

    return mpimg.imread(path)[:, :, :3]


def main(cmd, *args):
    if cmd == "size":
        path, w, h = args[0], int(args[1]), int(args[2])
        got = header_size(path)
        if got != (w, h):
            sys.exit(f"{path}: {got[0]}x{got[1]} pixels, expected {w}x{h}")
    elif cmd == "differ":
        a, b = pixels(args[0]), pixels(args[1])
        if a.shape != b.shape:
            return
        frac = float((abs(a - b).sum(axis=2) > 0.02).mean())
        if frac < 0.005:
            sys.exit(f"{args[0]} and {args[1]} are (nearly) the same picture ({100 * frac:.3f} % differ)")
    elif cmd == "drawn":
        p = pixels(args[0])
        background = p[0, 0]
        frac = float((abs(p - background).sum(axis=2) > 0.02).mean())
        if frac < 0.05:
            sys.exit(f"{args[0]}: only {100 * frac:.2f} % of the pixels are drawn")
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(*sys.argv[1:])
