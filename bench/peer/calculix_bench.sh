#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# CalculiX 2.20 and breastsim on the peers' gravity-loaded half cap
# (meshes/peers/README.md: mu = 2100 Pa, lambda = 0, rho = 970 kg/m^3,
# g = 9.81 m/s^2 along -z, base fixed, symmetry x = 0 sliding, no skin, P1),
# on the identical mesh: meshes/peers/halfcap_tagged.geo meshed by the gmsh
# library at the peers' lc (the peers' gmsh 4.8 command line, through the C
# API: bench/peer/peer_inp.py mesh).
#   CalculiX: C3D4 tetrahedra of that mesh, *HYPERFOAM N=2 (alpha 2, nu 0,
#     mu_1 = mu_2 = mu / 2: eq. (5) at lambda = 0, see peer_inp.py), 10
#     equal increments (*STATIC, DIRECT), residual tolerances 1e-8, 1 thread;
#     the apex displacement from the .dat (*NODE PRINT, 7 digits).
#   breastsim: `breastsim simulate` of a case whose geometry.mesh_file is that
#     mesh (read and checked as a user mesh), standing only, Newton with load
#     continuation, 1 thread; the apex from summary.json (nipple_m).
# Each run under /usr/bin/time -v: user CPU seconds and peak resident memory.
#
# Usage: bash bench/peer/calculix_bench.sh [BUILD_DIR]
#   BUILD_DIR default build (with breastsim); LCS="0.00675 0.00303" (the
#   default: the peers' 4871- and 50369-tet meshes; any lc works);
#   the scratch folder (mktemp) is removed unless KEEP_SCRATCH=1.
# Needs ccx (Debian: apt-get install calculix-ccx) and libgmsh 4.8.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
build="$(cd "${1:-$repo/build}" && pwd)"
bin="$build/breastsim"
geo="$repo/meshes/peers/halfcap_tagged.geo"
lcs="${LCS:-0.00675 0.00303}"
command -v ccx >/dev/null || { echo "calculix_bench: ccx not found (apt-get install calculix-ccx)"; exit 2; }
[ -x "$bin" ] || { echo "calculix_bench: $bin not built"; exit 2; }
scratch="$(mktemp -d /tmp/breastsim-peer-bench.XXXXXX)"
cleanup() { [ "${KEEP_SCRATCH:-0}" = 1 ] || rm -rf "$scratch"; }
trap cleanup EXIT
# One thread everywhere (the peers' CalculiX ran on 1).
export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1

# The peers' problem as a breastsim case on the mesh file $1/cap.msh.
write_case() {
  cat >"$1/peer.toml" <<'TOML'
[case]
name = "peer"
[geometry]
mesh_file = "cap.msh"
[tissue]
mu = 2100.0
lambda = 0.0
rho = 970.0
[gravity]
g = 9.81
[base]
fixed = true
[terms]
skin = false
base_springs = false
[postures]
names = ["standing"]
TOML
}
# "user_s peak_MB" of a /usr/bin/time -v report.
usage_of() {
  awk -F': ' '/User time/ {u = $2} /Maximum resident/ {m = $2 / 1024} END {printf "%.2f %.0f", u, m}' "$1"
}

rows=""
for lc in $lcs; do
  dir="$scratch/lc_$lc"
  mkdir -p "$dir"
  start=$(date +%s.%N)
  python3 "$here/peer_inp.py" mesh "$geo" "$lc" "$dir/cap.msh"
  mesh_s=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN {printf "%.2f", b - a}')
  counts="$(python3 "$here/peer_inp.py" inp "$dir/cap.msh" "$dir/cap.inp")"
  tets="${counts%% tets*}"
  echo "lc $lc: $counts (meshed in $mesh_s s)"

  (cd "$dir" && /usr/bin/time -v ccx -i cap >ccx.log 2>ccx.time) ||
    { tail -20 "$dir/ccx.log"; echo "calculix_bench: ccx failed on lc $lc"; exit 1; }
  read -r _ ccx_uy ccx_uz <<<"$(python3 "$here/peer_inp.py" apex "$dir/cap.dat")"
  read -r ccx_user ccx_mb <<<"$(usage_of "$dir/ccx.time")"

  write_case "$dir"
  /usr/bin/time -v "$bin" -q simulate "$dir/peer.toml" --out "$dir/breastsim" >"$dir/breastsim.log" \
    2>"$dir/breastsim.time" ||
    { tail -20 "$dir/breastsim.log" "$dir/breastsim.time"; echo "calculix_bench: breastsim failed on lc $lc"; exit 1; }
  read -r bs_uy bs_uz <<<"$(python3 -c 'import json, sys
n = json.load(open(sys.argv[1]))["postures"][0]["nipple_m"]
print(f"{n[1] - 0.06:.8e} {n[2]:.8e}")' "$dir/breastsim/summary.json")"
  read -r bs_user bs_mb <<<"$(usage_of "$dir/breastsim.time")"
  echo "  CalculiX : u_y $ccx_uy  u_z $ccx_uz  user ${ccx_user} s  peak ${ccx_mb} MB"
  echo "  breastsim: u_y $bs_uy  u_z $bs_uz  user ${bs_user} s  peak ${bs_mb} MB"
  rows+="| $lc | $tets | $ccx_uz | $bs_uz | $ccx_uy | $bs_uy | $ccx_user | $bs_user | $ccx_mb | $bs_mb |"$'\n'
done

echo
echo "| lc | tets | CalculiX u_z [m] | breastsim u_z [m] | CalculiX u_y [m] | breastsim u_y [m] |" \
     "CalculiX user [s] | breastsim user [s] | CalculiX peak [MB] | breastsim peak [MB] |"
echo "|---|---|---|---|---|---|---|---|---|---|"
printf "%s" "$rows"
echo "(1 thread each; breastsim's time is the whole simulate run: reading and checking the mesh,"
echo " set-up, solve, summary.json and the XDMF output)"
