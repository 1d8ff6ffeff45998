#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Wall time of the README's main job (`bash .ci/demo`) on a fresh Debian 12
# machine: a `debootstrap --variant=minbase bookworm` root holding only the
# base system, this repository's HEAD cloned into it, then .ci/demo run in it
# (apt-get, configure, build of the program, the default case), timed by
# stage from its output.
# Usage (as root; debootstrap installed; a Debian mirror reachable):
#   bash bench/fresh_demo.sh WORKDIR [MIRROR]
# WORKDIR must not exist; it is created and holds the root (about 2.6 GB
# afterwards), the demo's log and timing.json. It is never deleted here.
set -euo pipefail
[ $# -ge 1 ] || { echo "usage: bash bench/fresh_demo.sh WORKDIR [MIRROR]" >&2; exit 2; }
WORK="$1"; MIRROR="${2:-http://deb.debian.org/debian}"
REPO="$(cd "$(dirname "$0")/.." && pwd)"
[ "$(id -u)" = 0 ] || { echo "fresh_demo: must run as root (debootstrap, chroot)" >&2; exit 2; }
command -v debootstrap >/dev/null || { echo "fresh_demo: debootstrap is not installed" >&2; exit 2; }
[ ! -e "$WORK" ] || { echo "fresh_demo: WORKDIR '$WORK' exists; give a new path" >&2; exit 2; }
mkdir -p "$WORK"
ROOT="$WORK/root"

echo "fresh_demo: debootstrap (not timed) into $ROOT"
debootstrap --variant=minbase bookworm "$ROOT" "$MIRROR" > "$WORK/debootstrap.log" 2>&1
cp /etc/resolv.conf "$ROOT/etc/resolv.conf"
git clone -q "$REPO" "$ROOT/breastsim"

mounted=()
cleanup() { for ((i = ${#mounted[@]} - 1; i >= 0; i--)); do umount -l "${mounted[$i]}" || true; done; }
trap cleanup EXIT
for fs in proc sys dev dev/pts; do
  mkdir -p "$ROOT/$fs"
  case $fs in
    proc) mount -t proc proc "$ROOT/proc" ;;
    *) mount --bind "/$fs" "$ROOT/$fs" ;;
  esac
  mounted+=("$ROOT/$fs")
done

echo "fresh_demo: bash .ci/demo in the fresh root (timed)"
set +e
printf '%s %s\n' "$(date +%s.%N)" "fresh_demo: start" > "$WORK/demo.log"
chroot "$ROOT" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root \
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 \
  /bin/bash -c 'cd /breastsim && bash .ci/demo' 2>&1 |
  while IFS= read -r line; do printf '%s %s\n' "$(date +%s.%N)" "$line"; done >> "$WORK/demo.log"
rc=${PIPESTATUS[0]}
set -e
python3 - "$WORK/demo.log" "$rc" "$(git -C "$REPO" rev-parse --short HEAD)" "$(nproc)" <<'PY' | tee "$WORK/timing.json"
import json, re, sys
stamp = re.compile(r"^(\d+\.\d+) (.*)$")  # lines apt split with a carriage return have no stamp
lines = [m.groups() for m in map(stamp.match, open(sys.argv[1], errors="replace").read().split("\n")) if m]
t = [float(a) for a, _ in lines]
text = [b for _, b in lines]
first_build = next(i for i, s in enumerate(text) if re.match(r"\[ *\d+%\]", s))
built = max(i for i, s in enumerate(text) if "Built target breastsim" in s)
start, end = t[0], t[-1]
print(json.dumps({
    "commit": sys.argv[3], "cores": int(sys.argv[4]), "exit_code": int(sys.argv[2]),
    "wall_s": round(end - start, 1),
    "apt_and_configure_s": round(t[first_build] - start, 1),
    "build_s": round(t[built] - t[first_build], 1),
    "run_s": round(end - t[built], 1),
}, indent=1))
PY
exit "$rc"
