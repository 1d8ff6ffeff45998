#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-3.0-or-later
# Hostile-input catalogue: malformed input and dangerous output
# targets. Every case runs inside one scratch folder S; HOME points into it
# and the working directory is inside it, so no case can reach a real system
# path (the file-system root is checked on a fake root in test_output_safety).
# A refused case must exit 2, name the key/path/file, and leave S exactly as
# it was (every path, size, mtime and content hash); an accepted case must
# leave the sentinel files untouched.
set -u
BIN="$(readlink -f "$1")"; CASES="$(readlink -f "$2")"
S=$(mktemp -d); LOG=$(mktemp -d); trap 'rm -rf "$S" "$LOG"' EXIT
export HOME="$S/home"
export MPLCONFIGDIR="$LOG/mpl" XDG_CACHE_HOME="$LOG/cache" # caches of the picture tools
W="$S/home/work"               # working directory: $HOME/work
mkdir -p "$W/cases" "$S/sentinel" "$HOME"
echo "do not touch" > "$S/sentinel/keep.txt"
echo "my thesis" > "$HOME/thesis.txt"
cp "$CASES/default.toml" "$W/cases/default.toml"
CASE="$W/cases/default.toml"
QUICK=(--set geometry.mesh_size=0.012 --set postures.names=standing)
cd "$W"
fails=0; n=0

snapshot() { # every path below S with size, mtime and content hash
  (cd "$S" && find . -printf '%p %y %s %T@\n' | sort
   find . -type f -print0 | sort -z | xargs -0 -r sha256sum) | sha256sum
}
sentinels() { sha256sum "$S/sentinel/keep.txt" "$HOME/thesis.txt"; }
SENT=$(sentinels)

fail() { echo "FAIL $1: $2"; [ -f "$LOG/$1.err" ] && head -c 600 "$LOG/$1.err"; fails=$((fails + 1)); }

# refuse NAME FRAGMENT ARGS...: exit 2, message contains FRAGMENT, S unchanged.
refuse() {
  local name="$1" frag="$2"; shift 2
  n=$((n + 1))
  local before; before=$(snapshot)
  [ "${SNAPSHOT:-1}" = 1 ] || before=$(sentinels)
  timeout 120 "$BIN" -q "$@" >"$LOG/$name.out" 2>"$LOG/$name.err"
  local code=$?
  if [ "$code" -eq 124 ]; then fail "$name" "did not end within 120 s"; return; fi
  if [ "$code" -ne 2 ]; then fail "$name" "exit code $code (expected 2)"; return; fi
  if ! grep -qF -- "$frag" "$LOG/$name.err"; then fail "$name" "message lacks '$frag'"; return; fi
  local after; after=$(snapshot)
  [ "${SNAPSHOT:-1}" = 1 ] || after=$(sentinels)
  if [ "$after" != "$before" ]; then fail "$name" "the scratch folder changed"; return; fi
  echo "ok   $name: $(head -c 160 "$LOG/$name.err" | tr '\n' ' ')"
}

# accept NAME ARGS...: exit 0 and the sentinels untouched.
accept() {
  local name="$1"; shift
  n=$((n + 1))
  timeout 300 "$BIN" -q "$@" >"$LOG/$name.out" 2>"$LOG/$name.err"
  local code=$?
  if [ "$code" -ne 0 ]; then fail "$name" "exit code $code (expected 0)"; return 1; fi
  if [ "$(sentinels)" != "$SENT" ]; then fail "$name" "a sentinel file changed"; return 1; fi
  echo "ok   $name"
}

# check NAME CONDITION-DESCRIPTION COMMAND...: an extra assertion.
check() {
  local name="$1" what="$2"; shift 2
  n=$((n + 1))
  if "$@"; then echo "ok   $name: $what"; else fail "$name" "$what"; fi
}

no_staging_left() { ! ls -a "$W" "$S" | grep -q 'partial-'; }

# ---------------------------------------------------------------- output targets
mkdir -p "$W/mydata"; echo "chapter 1" > "$W/mydata/thesis.tex"
refuse out_user_folder "'$W/mydata': the folder is not empty" simulate "$CASE" --out mydata
mkdir -p "$W/repo/.git"; echo "ref: refs/heads/main" > "$W/repo/.git/HEAD"
refuse out_git_checkout "'$W/repo'" simulate "$CASE" --out repo
refuse out_holds_input "holds the input file" simulate "$CASE" --out cases
mkdir -p "$W/project/inputs"; cp "$CASE" "$W/project/inputs/patient.toml"
refuse out_holds_input_parent "holds the input file" simulate "$W/project/inputs/patient.toml" --out project
echo "data" > "$W/notes.txt"
refuse out_regular_file "'$W/notes.txt': it is a file" simulate "$CASE" --out notes.txt
refuse out_home "it is your home folder" simulate "$CASE" --out "$HOME"
refuse out_home_ancestor "it holds your home folder" simulate "$CASE" --out "$S"
refuse out_cwd "it is the working directory" simulate "$CASE" --out .
refuse out_parent_is_home "it is your home folder" simulate "$CASE" --out ..
refuse out_trailing_slash "'$W/mydata': the folder is not empty" simulate "$CASE" --out mydata/
refuse out_dotdot "'$W/mydata'" simulate "$CASE" --out cases/../mydata
ln -s "$W/mydata" "$W/link_to_mydata"
refuse out_symlink "'$W/mydata'" simulate "$CASE" --out link_to_mydata
refuse out_symlink_slash "'$W/mydata'" simulate "$CASE" --out link_to_mydata/
refuse out_empty_arg "--out is empty" simulate "$CASE" --out ""
mkdir -p "$W/empty"
refuse out_empty_no_force "pass --force" simulate "$CASE" --out empty
refuse out_force_nonempty "the folder is not empty" simulate "$CASE" --out mydata --force
refuse surgery_out_file "it is a file" surgery "$CASE" --out notes.txt
refuse sweep_out_user_folder "the folder is not empty" sweep "$CASE" --vary a=25 --out mydata
refuse converge_out_cwd "it is the working directory" converge "$CASE" --out .
refuse calibrate_out_user_folder "the folder is not empty" calibrate "$CASES/measurements_example.json" --out mydata

accept out_force_empty simulate "$CASE" "${QUICK[@]}" --out empty --force
check out_force_empty_marker "the taken-over folder carries the marker" test -f "$W/empty/.breastsim-result"
accept out_new_trailing_slash simulate "$CASE" "${QUICK[@]}" --out fresh/
check out_new_trailing_slash_result "fresh/ holds the result and no staging folder" \
  bash -c "test -f '$W/fresh/summary.json' && ! ls -a '$W/fresh' | grep -q partial"
check min_det_F_positive "summary.json reports min det F > 0 per posture" /usr/bin/python3 -c "
import json, sys
s = json.load(open('$W/fresh/summary.json'))
sys.exit(0 if s['postures'] and all(p['min_det_F'] > 0 for p in s['postures']) else 1)"
accept out_replace_marked simulate "$CASE" "${QUICK[@]}" --out fresh
check out_replace_marked_clean "the replaced folder holds no leftovers" no_staging_left

echo "my notes" > "$W/fresh/notes.txt"
refuse out_marked_foreign_file "it holds 'notes.txt', which breastsim did not write" simulate "$CASE" --out fresh
rm "$W/fresh/notes.txt"
mkdir -p "$W/forged"; echo '{"format": "breastsim result folder", "state": "staging"}' > "$W/forged/.breastsim-result"
refuse out_forged_marker "not a finished breastsim result" simulate "$CASE" --out forged
mkdir -p "$W/broken"; echo 'not json' > "$W/broken/.breastsim-result"
refuse out_broken_marker "cannot be read" simulate "$CASE" --out broken

# Default folder results/<case.name>: the name is a key, checked as one.
mkdir -p "$W/results/other"; echo "earlier run" > "$W/results/other/keep.txt"
refuse name_empty "key 'case.name' = \"\"" simulate "$CASE" --set case.name=
refuse name_dot "key 'case.name' = \".\"" simulate "$CASE" --set case.name=.
refuse name_dotdot "key 'case.name' = \"..\"" simulate "$CASE" --set case.name=..
refuse name_escape "key 'case.name' = \"../../etc\"" simulate "$CASE" --set case.name=../../etc
refuse name_backslash "path separator" simulate "$CASE" --set 'case.name=a\b'
printf '[case]\nname = "a\\u0000b"\n' > "$W/nul.toml"
refuse name_nul "control character" simulate "$W/nul.toml"
printf '[case]\nname = "line\\nbreak"\n' > "$W/newline.toml"
refuse name_newline "control character" simulate "$W/newline.toml"
refuse name_too_long "is 101 bytes long" simulate "$CASE" --set "case.name=$(printf 'x%.0s' {1..101})"

# Single-file outputs: only files breastsim wrote are replaced.
refuse measure_user_file "was not written by breastsim" measure "$CASE" --out notes.txt
refuse record_user_file "was not written by breastsim" record "$CASE" --out notes.txt
refuse measure_into_folder "is a folder, not a regular file" measure "$CASE" --out mydata
refuse record_over_input "an input file of this run" record "$CASE" --out "$CASE"
refuse checkpoint_user_file "the checkpoint" calibrate "$CASES/measurements_example.json" \
  --out cal --checkpoint notes.txt
refuse view_unmarked "has no .breastsim-result marker" view mydata

# Locks, signals and stale staging folders (while a run is busy, only the
# sentinels are compared: the busy run itself writes into S).
"$BIN" -q simulate "$CASE" --set geometry.mesh_size=0.003 --out busy >"$LOG/busy.out" 2>&1 &
busy=$!
for _ in $(seq 600); do [ -e "$W/.busy.breastsim-lock" ] && break; sleep 0.1; done
SNAPSHOT=0 refuse second_run_locked "'$W/busy': another breastsim run is writing there" simulate "$CASE" --out busy
kill -TERM "$busy"; wait "$busy"; code=$?
check sigterm_exit "SIGTERM exits 143 (got $code)" test "$code" -eq 143
check sigterm_clean "SIGTERM leaves no staging folder, lock or result" \
  bash -c "! ls -a '$W' | grep -q busy"

"$BIN" -q simulate "$CASE" --set geometry.mesh_size=0.003 --out intr >"$LOG/intr.out" 2>&1 &
intr=$!
for _ in $(seq 600); do ls "$W" | grep -q 'intr.partial' && break; sleep 0.1; done
kill -INT "$intr"; wait "$intr"; code=$?
check sigint_exit "SIGINT exits 130 (got $code)" test "$code" -eq 130
check sigint_clean "SIGINT removed the staging folder" bash -c "! ls -a '$W' | grep -q intr"

# A stale staging folder of a dead process (a marker with its pid) is removed
# by the next run into the same target; one of a live process, and a folder
# without the marker, are left alone.
dead=$(bash -c 'echo $$')
mkdir -p "$W/stale.partial-$dead"
printf '{"format": "breastsim result folder", "state": "staging", "pid": %s, "host": "%s"}\n' \
  "$dead" "$(hostname)" > "$W/stale.partial-$dead/.breastsim-result"
sleep 300 & live=$!
mkdir -p "$W/stale.partial-$live"
printf '{"format": "breastsim result folder", "state": "staging", "pid": %s, "host": "%s"}\n' \
  "$live" "$(hostname)" > "$W/stale.partial-$live/.breastsim-result"
mkdir -p "$W/stale.partial-1"; echo "user's" > "$W/stale.partial-1/file.txt"
accept stale_cleanup simulate "$CASE" "${QUICK[@]}" --out stale
check stale_dead_removed "the dead run's staging folder was removed" test ! -e "$W/stale.partial-$dead"
check stale_live_kept "the live run's staging folder was kept" test -d "$W/stale.partial-$live"
check stale_unmarked_kept "an unmarked *.partial-* folder was kept" test -f "$W/stale.partial-1/file.txt"
kill "$live" 2>/dev/null; wait "$live" 2>/dev/null

# ---------------------------------------------------------------- case files
refuse case_is_directory "is a folder, not a regular file" simulate "$W/cases"
python3 -c "print('a' + '.a' * 50000 + ' = 1')" > "$W/deep_dotted.toml"
refuse deep_dotted_key "keys nested deeper than 16 levels" simulate "$W/deep_dotted.toml"
python3 -c "print('[' + '.'.join(['t'] * 50000) + ']')" > "$W/deep_table.toml"
refuse deep_table_header "keys nested deeper than 16 levels" simulate "$W/deep_table.toml"
python3 -c "print('x = ' + '[' * 50000 + ']' * 50000)" > "$W/deep_array.toml"
refuse deep_array "values nested deeper than 16 levels" simulate "$W/deep_array.toml"
python3 -c "print('x = ' + '{a = ' * 50000 + '1' + '}' * 50000)" > "$W/deep_inline.toml"
refuse deep_inline_table "nested deeper than 16 levels" simulate "$W/deep_inline.toml"
printf '[geometry]\norder = 99999999999999999999\n' > "$W/int_overflow.toml"
refuse toml_integer_overflow "int_overflow.toml" simulate "$W/int_overflow.toml"
refuse set_integer_overflow "key 'geometry.order' = 1e30 is out of range" simulate "$CASE" --set geometry.order=1e30
refuse base_c_zero "key 'base.c' = 0" simulate "$CASE" --set base.c=0
refuse a_deg_90 "key 'incision.a_deg' = 90 is out of range: allowed (0, 90)" surgery "$CASE" --set incision.a_deg=90
check a_deg_keys_agree "breastsim keys advertises a_deg as (0, 90)" \
  bash -c "'$BIN' keys | grep 'incision.a_deg' | grep -qF '(0, 90)'"
refuse duplicate_posture "key 'postures.names' lists [\"supine\"] twice" simulate "$CASE" --set postures.names=standing,supine,supine
refuse duplicate_theta "key 'postures.theta_deg' lists [45] twice" simulate "$CASE" --set postures.theta_deg=45,45
refuse mesh_too_fine "tetrahedra needing about" simulate "$CASE" --set geometry.mesh_size=0.0002
refuse refinements_too_many "solver.max_memory_gb" simulate "$CASE" --set geometry.mesh_size=0.002 --set geometry.refinements=4
refuse memory_limit_key "above the limit of 0.01 GB" simulate "$CASE" --set solver.max_memory_gb=0.01
refuse nan_value "key 'tissue.mu' = nan" simulate "$CASE" --set tissue.mu=nan
refuse inf_value "key 'tissue.mu' = inf" simulate "$CASE" --set tissue.mu=inf

# case.resolved.toml is written by toml++: quotes, '#', backslashes and
# newlines in strings read back identically.
cat > "$W/strings.toml" <<'EOF'
[case]
name = 'say "hi" # not a comment'
[solver]
petsc_options = "-options_left 0 "
[postures]
names = ["standing"]
[geometry]
mesh_size = 0.012
EOF
accept resolved_strings simulate "$W/strings.toml" --out strings1
accept resolved_round_trip simulate "$W/strings1/case.resolved.toml" --out strings2
check resolved_identical "case.resolved.toml reads back to the same file" \
  cmp -s "$W/strings1/case.resolved.toml" "$W/strings2/case.resolved.toml"
check resolved_name_kept "the name survives the round trip" \
  grep -qF "name = 'say \"hi\" # not a comment'" "$W/strings2/case.resolved.toml"

# ---------------------------------------------------------------- PETSc options
refuse petsc_bad_ksp "Unable to find requested KSP type nosuchksp" simulate "$CASE" --petsc-options "-ksp_type nosuchksp"
refuse petsc_bad_pc "nosuchpc" simulate "$CASE" --petsc-options "-pc_type nosuchpc"
refuse petsc_case_key "solver.petsc_options" simulate "$CASE" --set "solver.petsc_options=-ksp_type nosuchksp"
refuse petsc_bad_value "-ksp_max_it" simulate "$CASE" --petsc-options "-ksp_max_it many"

# ---------------------------------------------------------------- sweeps
refuse sweep_list_key "key 'postures.names' is a list of strings" sweep "$CASE" --vary postures.names=standing,supine
refuse sweep_string_key "key 'solver.linear' is a string" sweep "$CASE" --vary solver.linear=direct,amg
refuse sweep_bool_value "key 'base.fixed' = \"maybe\"" sweep "$CASE" --vary base.fixed=true,maybe
refuse sweep_integer_range "key 'geometry.order' = 7 is out of range" sweep "$CASE" --vary geometry.order=1,7
refuse sweep_empty_value "empty value" sweep "$CASE" --vary a=25,,30
refuse sweep_no_standing "must include standing" sweep "$CASE" --vary a=25,30 --set postures.names=supine
check sweep_no_standing_early "refused before any surgery ran" \
  bash -c "! grep -q 'sweep:' '$LOG/sweep_no_standing.err' '$LOG/sweep_no_standing.out'"

# ---------------------------------------------------------------- JSON inputs
printf '{"units": "SI", "postures": [{"name": "standing", "nipple_y": 1e999}]}\n' > "$W/huge.json"
refuse json_huge_measurement "'huge.json' holds a number beyond the range of a double" calibrate huge.json --out cal
printf '{"format": "breastsim-recording/1", "postures": [], "noise_sigma": 1e999}\n' > "$W/huge_rec.json"
refuse json_huge_recording "'huge_rec.json' holds a number beyond the range" diagnose huge_rec.json --out diag
refuse json_directory "is a folder, not a regular file" calibrate "$W/cases" --out cal
refuse json_missing "does not exist" calibrate "$W/missing.json" --out cal

# ---------------------------------------------------------------- command line
refuse cli_unknown_subcommand "unknown subcommand 'simulat': did you mean 'simulate'?" simulat "$CASE"
refuse cli_unknown_option "--bogus" simulate "$CASE" --bogus
refuse cli_missing_case "case is required" simulate
refuse cli_no_subcommand "A subcommand is required"
refuse cli_bad_levels "breastsim: input error: --levels" converge "$CASE" --levels 9
refuse cli_misspelt_key "unknown key 'tisue.mu': did you mean 'tissue.mu'?" simulate "$CASE" --set tisue.mu=500

# ---------------------------------------------------------------- links and markers
# Nothing is written through a symbolic link: a picture replaced by a link,
# a link where the lock goes, a marker that lists a path outside its folder.
accept view_source simulate "$CASE" "${QUICK[@]}" --out viewed
ln -s "$S/sentinel/keep.txt" "$W/viewed/overview_link.png"
refuse view_foreign_link "'overview_link.png', which is a symbolic link" view viewed
rm "$W/viewed/overview_link.png"
if [ -f "$W/viewed/summary.json" ]; then
  mv "$W/viewed/summary.json" "$W/summary.saved"
  ln -s "$S/sentinel/keep.txt" "$W/viewed/summary.json"
  refuse view_listed_link "'summary.json', which is a symbolic link" view viewed
  rm "$W/viewed/summary.json"; mv "$W/summary.saved" "$W/viewed/summary.json"
fi
ln -s "$S/sentinel/lock-target" "$W/.linklock.breastsim-lock"
refuse lock_is_symlink "'.linklock.breastsim-lock' beside it is a symbolic link" simulate "$CASE" --out linklock
check lock_target_absent "the lock's link target was not created" test ! -e "$S/sentinel/lock-target"
rm "$W/.linklock.breastsim-lock"
mkfifo "$W/.fifolock.breastsim-lock"
refuse lock_is_fifo "is a named pipe (FIFO), not breastsim's lock file" simulate "$CASE" --out fifolock
rm "$W/.fifolock.breastsim-lock"
mkdir -p "$W/absmarker"
echo '{"format": "breastsim result folder", "state": "complete", "files": ["/x"]}' > "$W/absmarker/.breastsim-result"
refuse marker_absolute_path "lists '/x', which is not a path inside the folder" simulate "$CASE" --out absmarker
mkdir -p "$W/upmarker"
echo '{"format": "breastsim result folder", "state": "complete", "files": ["../../x"]}' > "$W/upmarker/.breastsim-result"
refuse marker_parent_path "lists '../../x', which is not a path inside the folder" simulate "$CASE" --out upmarker
mkdir -p "$W/linkmarker"; ln -s "$S/sentinel/keep.txt" "$W/linkmarker/.breastsim-result"
refuse marker_is_link "its .breastsim-result is a symbolic link" simulate "$CASE" --out linkmarker
ln -s "$W/nowhere" "$W/dangling"
refuse out_dangling_link "it is a symbolic link to nothing" simulate "$CASE" --out dangling
mkfifo "$W/fifo"
refuse out_fifo "it is a named pipe (FIFO)" simulate "$CASE" --out fifo
ln -s "$S/sentinel/keep.txt" "$W/measure_link.json"
refuse measure_out_link "it is a symbolic link to a regular file" measure "$CASE" --out measure_link.json
ln -s loop_b.toml "$W/loop_a.toml"; ln -s loop_a.toml "$W/loop_b.toml"
refuse case_symlink_loop "is a loop of symbolic links" simulate "$W/loop_a.toml"
ln -s "$W/nowhere.toml" "$W/dangling.toml"
refuse case_dangling_link "is a symbolic link to nothing" simulate "$W/dangling.toml"
mkfifo "$W/case_fifo.toml"
refuse case_fifo "is a named pipe (FIFO), not a regular file" simulate "$W/case_fifo.toml"
# A file of the user's with the staging folder's name (the pid is known: exec).
printf '#!/bin/sh\necho "user data" > "%s/held.partial-$$"\nexec "%s" "$@"\n' "$W" "$BIN" > "$LOG/held.sh"
chmod +x "$LOG/held.sh"
BIN="$LOG/held.sh" SNAPSHOT=0 refuse staging_name_taken "'$W/held': 'held.partial-" simulate "$CASE" --out held
check staging_name_taken_kept "the user's file with the staging name is untouched" \
  bash -c "grep -qx 'user data' '$W'/held.partial-*"
rm -f "$W"/held.partial-*

# ---------------------------------------------------------------- PETSc options that touch files
refuse petsc_log_view_file "-log_view :" simulate "$CASE" --petsc-options "-log_view :$S/sentinel/keep.txt"
refuse petsc_viewer_filename "-viewer_binary_filename is not accepted" simulate "$CASE" --petsc-options "-viewer_binary_filename $W/out.bin"
refuse petsc_options_file "-options_file is not accepted" simulate "$CASE" --petsc-options "-options_file /dev/zero"
refuse petsc_history "-history is not accepted" simulate "$CASE" --petsc-options "-history $W/h.txt"
refuse petsc_malloc_dump "-malloc_dump" simulate "$CASE" --petsc-options "-malloc_dump $W/m.txt"
refuse petsc_binary_view "-ksp_view binary" simulate "$CASE" --petsc-options "-ksp_view binary"
refuse petsc_monitor_file "-ksp_monitor" simulate "$CASE" --petsc-options "-ksp_monitor ascii:$W/mon.txt"
refuse petsc_debugger "-start_in_debugger is not accepted" simulate "$CASE" --petsc-options "-start_in_debugger"
refuse petsc_case_file_option "key 'solver.petsc_options'" simulate "$CASE" --set "solver.petsc_options=-log_view :$W/log.txt"
accept petsc_stdout_viewer simulate "$CASE" "${QUICK[@]}" --petsc-options "-ksp_converged_reason -ksp_view ::ascii_info" --out petscok
check petsc_stdout_viewer_printed "the ascii viewer printed to standard output" grep -q "KSP Object" "$LOG/petsc_stdout_viewer.out"

# ---------------------------------------------------------------- JSON bounds and duplicates
printf '{"units": "mm", "units": "SI", "postures": []}\n' > "$W/dup_units.json"
refuse json_duplicate_key "the key 'units' appears twice" calibrate dup_units.json --out cal
printf '{"format": "breastsim-recording/1", "noise_sigma": 0.001, "noise_sigma": 0.002, "postures": []}\n' > "$W/dup_sigma.json"
refuse json_duplicate_recording_key "the key 'noise_sigma' appears twice" diagnose dup_sigma.json --out diag
python3 -c "
import sys
sys.stdout.write('{\"format\": \"breastsim-recording/1\", \"noise_sigma\": 0.001, \"postures\": [{\"name\": \"standing\", \"theta_deg\": 0, \"points\": [')
sys.stdout.write(','.join(['[0.01,0.01,0.01]'] * 1000001))
sys.stdout.write(']}]}')" > "$W/many_points.json"
refuse recording_too_many_points "allowed at most 1000000 per posture" diagnose many_points.json --out diag
rm "$W/many_points.json"
truncate -s 200M "$W/huge_file.json"
refuse json_file_too_large "is 200 MB: allowed at most 128 MB" diagnose huge_file.json --out diag
rm "$W/huge_file.json"
refuse set_long_value "key 'tissue.mu'" simulate "$CASE" --set "tissue.mu=$(head -c 100000 /dev/zero | tr '\0' '7')x"
check set_long_value_short "the 100 kB value is not echoed whole" test "$(wc -c < "$LOG/set_long_value.err")" -lt 1000

# ---------------------------------------------------------------- signals and broken streams
# SIGHUP (a closed terminal) ends the run like SIGTERM: exit 129, nothing left.
"$BIN" -q simulate "$CASE" --set geometry.mesh_size=0.003 --out hup >"$LOG/hup.out" 2>&1 &
hup=$!
for _ in $(seq 600); do ls "$W" | grep -q 'hup.partial' && break; sleep 0.1; done
kill -HUP "$hup"; wait "$hup"; code=$?
check sighup_exit "SIGHUP exits 129 (got $code)" test "$code" -eq 129
check sighup_clean "SIGHUP leaves no staging folder, lock or result" bash -c "! ls -a '$W' | grep -q hup"
# A reader that went away (| true): SIGPIPE ends the run, exit 141, nothing left behind.
( "$BIN" simulate "$CASE" --set geometry.mesh_size=0.004 --out piped 2>"$LOG/pipe.err"; echo $? > "$LOG/pipe.code" ) | true
code=$(cat "$LOG/pipe.code")
check sigpipe_exit "a closed stdout exits 141 (got $code)" test "$code" -eq 141
check sigpipe_clean "a closed stdout leaves no staging folder or lock" \
  bash -c "! ls -a '$W' | grep -q 'piped.partial\|piped.breastsim-lock'"
check sigpipe_no_petsc "no PETSc or MPI abort text" bash -c "! grep -q 'PETSC ERROR\|MPI_ABORT' '$LOG/pipe.err'"
# Standard output on a full device: one line, exit 1, no PETSc stack.
n=$((n + 1))
"$BIN" -q simulate "$CASE" "${QUICK[@]}" --out devfull >/dev/full 2>"$LOG/devfull.err"; code=$?
if [ "$code" -ne 1 ]; then fail devfull "exit code $code (expected 1)"
elif ! grep -q "cannot write to standard output" "$LOG/devfull.err"; then fail devfull "message lacks 'cannot write to standard output'"
elif grep -q "PETSC ERROR" "$LOG/devfull.err"; then fail devfull "PETSc's stack was printed"
else echo "ok   devfull: $(head -c 120 "$LOG/devfull.err")"; fi
# A working directory that was deleted; a $TMPDIR that does not exist; no orted on PATH.
mkdir -p "$W/gone"
n=$((n + 1))
(cd "$W/gone" && rmdir "$W/gone" && "$BIN" -q keys >/dev/null 2>"$LOG/gone.err"); code=$?
if [ "$code" -ne 1 ] || ! grep -q "working directory cannot be read" "$LOG/gone.err"; then fail cwd_deleted "exit $code: $(head -c 200 "$LOG/gone.err")"
else echo "ok   cwd_deleted: $(head -c 120 "$LOG/gone.err")"; fi
n=$((n + 1))
TMPDIR="$S/no_such_tmp/x" "$BIN" -q keys >/dev/null 2>"$LOG/tmpdir.err"; code=$?
if [ "$code" -ne 1 ] || ! grep -q "TMPDIR" "$LOG/tmpdir.err"; then fail tmpdir_missing "exit $code: $(head -c 200 "$LOG/tmpdir.err")"
elif [ -e "$S/no_such_tmp" ]; then fail tmpdir_missing "the missing TMPDIR was created"
else echo "ok   tmpdir_missing: $(head -c 120 "$LOG/tmpdir.err")"; fi
check no_orted_on_path "runs alone without orted on PATH" bash -c "PATH=/nonexistent '$BIN' -q keys >/dev/null 2>'$LOG/path.err'"
# A file-size limit (ulimit -f): the write fails with a message, no core dump, nothing left.
n=$((n + 1))
(ulimit -f 64; "$BIN" -q simulate "$CASE" --set postures.names=standing --set geometry.mesh_size=0.005 --out fsize >/dev/null 2>"$LOG/fsize.err"); code=$?
if [ "$code" -ne 1 ]; then fail file_size_limit "exit code $code (expected 1)"
elif ! grep -q "File too large" "$LOG/fsize.err"; then fail file_size_limit "message lacks 'File too large': $(head -c 300 "$LOG/fsize.err")"
elif grep -q "HDF5-DIAG" "$LOG/fsize.err"; then fail file_size_limit "HDF5's error stack was printed"
elif ls -a "$W" | grep -q "fsize"; then fail file_size_limit "a staging folder or result was left"
else echo "ok   file_size_limit: $(grep -o "cannot write.*" "$LOG/fsize.err" | head -1 | head -c 160)"; fi

# ---------------------------------------------------------------- a full disk
# In a private mount namespace (root only), a 256 kB tmpfs holds the output:
# the HDF5 write of the displacement fails.
if unshare -m true 2>/dev/null; then
  n=$((n + 1))
  mkdir -p "$W/tiny"
  unshare -m bash -c "mount -t tmpfs -o size=256k tmpfs '$W/tiny' && \
    '$BIN' -q simulate '$CASE' --set postures.names=standing --set geometry.mesh_size=0.004 \
      --out '$W/tiny/out'; echo \$? > '$LOG/disk.code'; \
    ls -a '$W/tiny' > '$LOG/disk.ls'" >"$LOG/disk.out" 2>"$LOG/disk.err"
  if [ "$(cat "$LOG/disk.code")" = 0 ]; then fail disk_full "the run succeeded on a 256 kB disk"
  elif ! grep -q "displacement_standing.h5': no space left on device" "$LOG/disk.err"; then fail disk_full "message lacks 'no space left on device'"
  elif grep -q partial "$LOG/disk.ls"; then fail disk_full "a staging folder was left on the full disk"
  elif grep -q "HDF5-DIAG\|Traceback" "$LOG/disk.err"; then fail disk_full "HDF5's error stack or a Python traceback was printed"
  else echo "ok   disk_full: $(grep -o "cannot write.*" "$LOG/disk.err" | head -1)"; fi
  rmdir "$W/tiny"
else
  echo "note disk_full: no mount namespace here (not root); the full-disk case is not run"
fi

check nothing_left_behind "no staging folders or lock files remain" \
  bash -c "! find '$S' -name '*.partial-*' -newer '$S/sentinel/keep.txt' | grep -v 'stale.partial' | grep -q . \
           && ! find '$S' -name '*.breastsim-lock' | grep -q ."
check sentinels_intact "the sentinel files are unchanged" test "$(sentinels)" = "$SENT"
check no_fltk_prefs "nothing was written into HOME by gmsh/FLTK" test ! -e "$HOME/.fltk"
check no_internal_prefixes "no message carries 'filesystem error:' or '[json.exception' prefixes" \
  bash -c "! grep -l 'filesystem error:\|\[json.exception' '$LOG'/*.err"

echo "$((n - fails)) passed, $fails failed"
[ "$fails" -eq 0 ]
