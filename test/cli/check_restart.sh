#!/usr/bin/env bash
# Restart (issue 25 item 4): a run continued from its restart data is bit-identical to the
# uninterrupted run at every later step. Each case runs a deck (a) uninterrupted with restart
# data every few steps, (b) stopped after step K (--stop-after-step, the test aid that stands
# for a run that dies; one case is killed with SIGKILL instead) and (c) continued from (b)'s
# checkpoint file (FE1 and model C continue from (a)'s own data); restart_compare.py then
# compares every dataset and attribute of the continued results with (a)'s (timings aside) and
# the restart data of every later step (the whole state: displacements, point states, matrix
# values, counters). Cases: friction with
# full Newton-Raphson and LINESEARCH=energy (LU tangents), BFGS, every solution method on a
# deck whose supports change between stages, a post-tensioned bar, a group born in stage 2,
# FE1 (400 steps) and a model C case (three stages), with restart points mid-stage and at
# stage boundaries; and the bad input (another model's restart data, a missing file, a step
# the file does not hold, --step without --restart, a results file that holds no restart data,
# restart data of an earlier layout).
# FEPS names the build to check (default: the release build, which FE1 and model C need).
set -uo pipefail
cd "$(dirname "$0")/../.."
if [ -z "${FEPS:-}" ]; then
  fpm build --profile release >/dev/null 2>&1 || { echo "check_restart: build failed" >&2; exit 1; }
  FEPS=$(fpm run --profile release --runner echo 2>/dev/null | tail -n 1)
fi
feps=$FEPS
[ -x "$feps" ] || { echo "check_restart: cannot find the feps executable" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0
ok() { pass=$((pass + 1)); echo "  ok   $1"; }
bad() { fail=$((fail + 1)); echo "  FAIL $1"; }
compare=test/cli/restart_compare.py

# case NAME DECK EVERY "K1 K2 ..." [options...]: uninterrupted with restart data every EVERY
# steps; for each K a run stopped after K and one continued from the stopped run's data. With
# own=1 the continued run starts from the uninterrupted run's own data of step K, and no run is
# stopped (the thesis decks: a stopped run would repeat K steps to write the data that the
# uninterrupted run wrote at step K; the small decks check the stopped runs).
case_() {
  local name=$1 deck=$2 every=$3 ks=$4; shift 4
  "$feps" "$deck" -q -o "$tmp/$name.h5" --restart-every "$every" "$@" >"$tmp/out" 2>&1 \
    || { bad "$name: the uninterrupted run: $(head -c 300 "$tmp/out")"; return; }
  local k from
  for k in $ks; do
    from=$tmp/$name.restart.h5
    if [ -z "${own:-}" ]; then
      from=$tmp/${name}_stop$k.restart.h5
      "$feps" "$deck" -q -o "$tmp/${name}_stop$k.h5" --restart-every "$every" --stop-after-step "$k" "$@" \
        >"$tmp/out" 2>&1
      if [ $? -ne 1 ] || [ -e "$tmp/${name}_stop$k.h5" ] || [ -e "$tmp/${name}_stop$k.h5.part" ] \
         || [ ! -e "$from" ]; then
        bad "$name: stopped after $k: exit 1, no results, the checkpoint kept: $(head -c 300 "$tmp/out")"
        continue
      fi
    fi
    "$feps" "$deck" -q -o "$tmp/${name}_cont$k.h5" --restart "$from" --step "$k" \
      --restart-every "$every" "$@" >"$tmp/out" 2>&1 \
      || { bad "$name: continued after $k: $(head -c 300 "$tmp/out")"; continue; }
    python3 "$compare" "$tmp/$name.h5" "$tmp/${name}_cont$k.h5" "$k" >"$tmp/cmp" 2>&1 \
      && ok "$name: continued after step $k: $(tail -n 1 "$tmp/cmp")" \
      || bad "$name: continued after step $k: $(head -c 600 "$tmp/cmp")"
    if [ "$k" -lt "$(python3 -c 'import sys, h5py; print(max(int(s) for s in h5py.File(sys.argv[1])["restart/steps"][...]))' "$tmp/$name.restart.h5")" ]; then
      python3 "$compare" --checkpoints "$tmp/$name.restart.h5" "$tmp/${name}_cont$k.restart.h5" "$k" >"$tmp/cmp" 2>&1 \
        && ok "$name: ... the whole state: $(tail -n 1 "$tmp/cmp")" \
        || bad "$name: the restart data after step $k: $(head -c 600 "$tmp/cmp")"
    fi
  done
}

# Full Newton-Raphson with LINESEARCH=energy (exact LU tangents): stage boundary (1), mid-stage (5).
case_ friction test/data/friction_pull.dat 1 "1 5"
# ACCELERATION=bfgs with initial stiffness, two one-step stages: the boundary.
case_ bfgs test/data/block_shear.dat 1 "1"
# Every method on a deck whose supports change in stage b: before the change (5, a boundary)
# and after it, mid-stage (7).
for m in euler modified-euler newton-raphson modified-newton-raphson initial-stiffness full-newton-raphson; do
  case_ "support_$m" test/data/slide_1dof_support_change.dat 1 "5 7" --method "$m"
done
# Tendons post-tensioned in stage 2 (pulling on their nodes, not yet bonded) and bonded (born
# carrying their force) in stage 3: mid-stage (4) and at the boundary before the bond (7).
case_ post test/data/prestress_post.dat 1 "4 7"
# A group born in stage 2.
case_ birth test/data/activate_block.dat 1 "1"
# FE1 (400 steps of initial stiffness) after step 390, and model C (stages of 1, 250 and 100
# steps) at the boundary of stages 2 and 3 (251), from the uninterrupted runs' data; model C
# stopped mid-stage 2 (150) and continued from the file's last point.
own=1 case_ FE1 input/modelB/FE1.dat 130 "390"
# FE1 with --mixed-precision: the restored factor's single-precision copy comes back at the
# first solve (the restart data keep the solves made with it), so the same bits follow too.
own=1 case_ FE1_mixed input/modelB/FE1.dat 200 "200" --mixed-precision
own=1 case_ modelC input/modelC/C_G300_nu0.1_b0.09.dat 251 "251"
"$feps" input/modelC/C_G300_nu0.1_b0.09.dat -q -o "$tmp/mc150.h5" --restart-every 150 --stop-after-step 150 \
  >/dev/null 2>&1
"$feps" input/modelC/C_G300_nu0.1_b0.09.dat -q -o "$tmp/mc150_cont.h5" --restart "$tmp/mc150.restart.h5" \
  >"$tmp/out" 2>&1 || bad "modelC: continued after 150: $(head -c 300 "$tmp/out")"
python3 "$compare" "$tmp/modelC.h5" "$tmp/mc150_cont.h5" 150 >"$tmp/cmp" 2>&1 \
  && ok "modelC: continued after step 150 (mid-stage, the file's last point by default): $(tail -n 1 "$tmp/cmp")" \
  || bad "modelC: continued after step 150: $(head -c 600 "$tmp/cmp")"

# A run killed (SIGKILL) leaves its last complete checkpoint; continued from it, FE1 ends as
# the uninterrupted run does.
"$feps" input/modelB/FE1.dat -q -o "$tmp/fe1_kill.h5" --restart-every 20 >/dev/null 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [ -e "$tmp/fe1_kill.restart.h5" ] && break
  sleep 0.1
done
sleep 1
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
if [ -e "$tmp/fe1_kill.restart.h5" ]; then
  last=$(python3 -c 'import sys, h5py; print(max(int(s) for s in h5py.File(sys.argv[1])["restart/steps"][...]))' \
         "$tmp/fe1_kill.restart.h5")
  "$feps" input/modelB/FE1.dat -q -o "$tmp/fe1_kill_cont.h5" --restart "$tmp/fe1_kill.restart.h5" >"$tmp/out" 2>&1 \
    && python3 "$compare" "$tmp/FE1.h5" "$tmp/fe1_kill_cont.h5" "$last" >"$tmp/cmp" 2>&1 \
    && ok "FE1 killed after its checkpoint of step $last, continued: $(tail -n 1 "$tmp/cmp")" \
    || bad "FE1 killed and continued after $last: $(head -c 600 "$tmp/out" "$tmp/cmp")"
else
  bad "FE1 killed: no checkpoint file left"
fi

# Bad input: one line, exit 2, no result file of the continued run.
refused() {  # name pattern command...
  local name=$1 pattern=$2; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  if [ "$got" -eq 2 ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "^feps: error: .*$pattern" "$tmp/err" \
     && [ ! -e "$tmp/refused.h5" ] && [ ! -e "$tmp/refused.h5.part" ]; then
    ok "$name (exit 2): $(head -c 200 "$tmp/err")"
  else
    bad "$name: exit $got, expected 2, one line with \"$pattern\", no result file: $(head -c 300 "$tmp/err")"
  fi
}
refused "restart data of another model" "restart data of another model" \
  "$feps" test/data/block_shear.dat -o "$tmp/refused.h5" --restart "$tmp/friction.restart.h5"
refused "restart data of the same deck under another method" "restart data of another model" \
  "$feps" test/data/slide_1dof_support_change.dat -o "$tmp/refused.h5" --restart "$tmp/support_euler.restart.h5" \
  --method initial-stiffness
"$feps" test/data/friction_pull.dat -q -o "$tmp/flags.h5" --steps 4 --tolerance 1e-3 --restart-every 1 \
  --stop-after-step 3 >/dev/null 2>&1
refused "restart data written under --steps 4 --tolerance 1e-3, resumed with --steps 4 alone" \
  "restart data of another model" \
  "$feps" test/data/friction_pull.dat -o "$tmp/refused.h5" --restart "$tmp/flags.restart.h5" --steps 4
"$feps" test/data/friction_pull.dat -q -o "$tmp/flags_cont.h5" --steps 4 --tolerance 1e-3 \
  --restart "$tmp/flags.restart.h5" >"$tmp/out" 2>&1 \
  && ok "... and resumed with both: exit 0" || bad "resumed with --steps 4 --tolerance 1e-3: $(head -c 300 "$tmp/out")"
refused "a missing restart file" "no such file" \
  "$feps" test/data/friction_pull.dat -o "$tmp/refused.h5" --restart "$tmp/no_such.restart.h5"
refused "a step the restart file does not hold" "holds no restart data of step 99 (--step; it holds steps 1 2" \
  "$feps" test/data/friction_pull.dat -o "$tmp/refused.h5" --restart "$tmp/friction.restart.h5" --step 99
refused "a results file as restart data" "holds no restart data (no /restart/steps" \
  "$feps" test/data/friction_pull.dat -o "$tmp/refused.h5" --restart "$tmp/friction.h5"
# restart data of an earlier layout (its counters 14 integers, before the mixed-precision ones)
python3 - "$tmp/friction.restart.h5" "$tmp/older.restart.h5" <<'PY'
import shutil, sys, h5py
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "r+") as f:
    for name, g in f["restart"].items():
        if name.startswith("step_"):
            ints = g["ints"][...][:14]
            del g["ints"]
            g["ints"] = ints
PY
refused "restart data of an earlier layout" "the restart data of step 5 cannot be read" \
  "$feps" test/data/friction_pull.dat -o "$tmp/refused.h5" --restart "$tmp/older.restart.h5" --step 5
refused "a restart point at the run's last step" "its restart point is step 11, the last of the run .*nothing to continue" \
  "$feps" test/data/friction_pull.dat -o "$tmp/refused.h5" --restart "$tmp/friction.restart.h5" --step 11
refused "--step without --restart" "needs --restart FILE" \
  "$feps" test/data/friction_pull.dat -o "$tmp/refused.h5" --step 3
refused "--restart-every 0" "--restart-every takes a whole number from 1" \
  "$feps" test/data/friction_pull.dat -o "$tmp/refused.h5" --restart-every 0

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
