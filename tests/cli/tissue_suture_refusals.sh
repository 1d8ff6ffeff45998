#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# The tissue-to-tissue suture (terms.tissue_suture) refuses, with exit code 2,
# a message naming it and no output left behind: on a mesh without the faces
# suture_a / suture_b, on one MPI rank and on two (the refusal is collective).
set -u
BIN="$1"; CASES="$2"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
fails=0; n=0
check() { # name, expected message fragment, command...
  local name="$1" frag="$2"; shift 2
  n=$((n + 1))
  "$@" --out "$work/out_$name" >"$work/$name.out" 2>"$work/$name.err"
  local code=$?
  if [ "$code" -ne 2 ]; then
    echo "FAIL $name: exit code $code (expected 2)"; cat "$work/$name.err"; fails=$((fails + 1)); return
  fi
  if ! grep -qF -- "$frag" "$work/$name.err" || ! grep -qF "tissue_suture" "$work/$name.err"; then
    echo "FAIL $name: message lacks '$frag' or the term name:"; cat "$work/$name.err"; fails=$((fails + 1)); return
  fi
  if ls -d "$work"/out_"$name"* >/dev/null 2>&1; then
    echo "FAIL $name: output left behind"; fails=$((fails + 1)); return
  fi
  echo "ok   $name: $(head -c 200 "$work/$name.err")"
}
args=(simulate "$CASES/default.toml" --set geometry.mesh_size=0.014 --set postures.names=standing
      --set terms.tissue_suture=true)
check no_faces "has no facets tagged" "$BIN" -q "${args[@]}"
check two_ranks "has no facets tagged" mpirun -n 2 "$BIN" -q "${args[@]}"
echo "$((n - fails)) passed, $fails failed"
[ "$fails" -eq 0 ]
