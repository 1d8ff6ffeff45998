#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Bad input: every case must fail with exit code 2, a message naming the
# problem, and leave no output folder behind.
set -u
BIN="$1"; CASES="$2"
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
cd "$work"
fails=0; n=0

expect_error() { # name, expected message fragment, subcommand args...
  local name="$1" frag="$2"; shift 2
  n=$((n + 1))
  "$BIN" -q "$@" --out "$work/out_$name" >"$work/$name.out" 2>"$work/$name.err"
  local code=$?
  if [ "$code" -ne 2 ]; then
    echo "FAIL $name: exit code $code (expected 2)"; cat "$work/$name.err"; fails=$((fails + 1)); return
  fi
  if ! grep -qF -- "$frag" "$work/$name.err"; then
    echo "FAIL $name: message lacks '$frag':"; cat "$work/$name.err"; fails=$((fails + 1)); return
  fi
  if ls -d "$work"/out_"$name"* >/dev/null 2>&1; then
    echo "FAIL $name: output left behind"; fails=$((fails + 1)); return
  fi
  echo "ok   $name: $(head -c 200 "$work/$name.err")"
}

printf '[geometry\nR = 0.07\n' > bad.toml
printf '[geometry]\nR = 0.07\nradius = 3\n' > unknown.toml
printf '[tissue]\nmu = -5.0\n' > negmu.toml
printf '[geometry]\nR = 0.0\n' > r0.toml
printf '[geometry]\nR = -0.07\n' > rneg.toml
printf '[geometry]\nR = 0.07\nH = 0.5\n' > hbig.toml
printf '[postures]\ntheta_deg = [200.0]\n' > angle.toml
printf '[postures]\nnames = ["handstand"]\n' > posture.toml
printf '[tissue]\nmu = "soft"\n' > type.toml
printf '[solver]\nlinear = "magic"\n' > choice.toml
printf '[geometry]\norder = 3\n' > order.toml
printf '[geometry]\nrim_size_ratio = 0.05\n' > rim.toml
printf '[chest_wall]\nk = -1.0\n' > wall.toml

expect_error missing_file "does not exist" simulate "$work/nope.toml"
expect_error bad_toml "not valid TOML" simulate bad.toml
expect_error unknown_key "unknown key 'geometry.radius'" simulate unknown.toml
expect_error negative_modulus "key 'tissue.mu' = -5" simulate negmu.toml
expect_error zero_radius "key 'geometry.R' = 0" simulate r0.toml
expect_error negative_radius "key 'geometry.R' = -0.07" simulate rneg.toml
expect_error absurd_height "key 'geometry.H' = 0.5" simulate hbig.toml
expect_error angle_range "key 'postures.theta_deg'" simulate angle.toml
expect_error unknown_posture "\"handstand\"" simulate posture.toml
expect_error wrong_type "expected number" simulate type.toml
expect_error bad_choice "key 'solver.linear'" simulate choice.toml
expect_error bad_order "key 'geometry.order' = 3" simulate order.toml
expect_error rim_grading "key 'geometry.rim_size_ratio' = 0.05" simulate rim.toml
expect_error negative_wall "key 'chest_wall.k' = -1" simulate wall.toml
expect_error bad_set "key 'tissue.lambda' = \"abc\" is not a number" simulate "$CASES/default.toml" --set tissue.lambda=abc
expect_error set_unknown "unknown key 'tissue.nu'" simulate "$CASES/default.toml" --set tissue.nu=0.3
expect_error set_syntax "--set expects key=value" simulate "$CASES/default.toml" --set tissue.mu

# Surgery: incision parameters that make a point undefined are rejected
# before any meshing, naming the parameter.
expect_error incision_s "key 'incision.s'" surgery "$CASES/default.toml" --set incision.s=0.09
expect_error incision_h "key 'incision.h'" surgery "$CASES/default.toml" --set incision.h=0.07
expect_error incision_angle "key 'incision.a_deg'" surgery "$CASES/default.toml" --set incision.a_deg=60
expect_error incision_d "key 'incision.d'" surgery "$CASES/default.toml" --set incision.d=0.08
expect_error sweep_vary "unknown key 'q'" sweep "$CASES/default.toml" --vary q=1,2
expect_error base_held_by_nothing "leaves the base held by nothing" simulate "$CASES/default.toml" --set terms.base_springs=false
expect_error unknown_hidden "unknown candidate physics 'dark_matter'" record "$CASES/default.toml" --hidden dark_matter
expect_error hidden_already_on "nothing would be hidden" record "$CASES/default.toml" --hidden skin

echo "$((n - fails)) passed, $fails failed"
[ "$fails" -eq 0 ]
