#!/usr/bin/env bash
# scripts/campaign.sh --slurm against a real Slurm (issue 29): scripts/slurm_localhost.sh makes a
# one-node Slurm of this machine (installing Debian's slurm-wlm and munge when missing), then a
# small campaign runs through it as a job array: its CSV must be the local campaign's (the same
# decks run by xargs) but for the timings, and a second call must submit only the case that
# failed. FEPS names the feps to run (default: fpm's debug build).
set -uo pipefail
cd "$(dirname "$0")/../.."
feps=${FEPS:-$PWD/$(fpm run --runner echo 2>/dev/null | tail -n 1)}
tmp=$(mktemp -d)
name=check_slurm_$$
trap 'bash scripts/slurm_localhost.sh stop "$tmp/slurm" >/dev/null 2>&1; rm -rf "$tmp" "results/$name" "results/${name}_local"' EXIT
pass=0; fail=0
ok() { pass=$((pass + 1)); echo "  ok   $1"; }
bad() { fail=$((fail + 1)); echo "  FAIL $1"; }

bash scripts/slurm_localhost.sh start "$tmp/slurm" >"$tmp/start" 2>&1 || { cat "$tmp/start"; echo "check_slurm: no Slurm"; exit 1; }
export SLURM_CONF=$tmp/slurm/slurm.conf
decks=(test/data/cube.dat test/data/soil_column.dat test/data/overflow_solution.dat)   # the last fails (exit 1)

FEPS=$feps bash scripts/campaign.sh --slurm "$name" "${decks[@]}" >"$tmp/slurm1" 2>&1; st=$?
[ $st -eq 1 ] && grep -q "^submit 3 case(s) as a Slurm job array" "$tmp/slurm1" \
  && grep -q "1 of 3 cases not finished: overflow_solution (failed)" "$tmp/slurm1" \
  && ok "campaign.sh --slurm: one job array of 3 cases, the failed one named, exit 1" \
  || bad "campaign.sh --slurm: exit $st: $(tail -c 400 "$tmp/slurm1")"
ls results/"$name"/slurm/task_*.out >/dev/null 2>&1 && ok "each task's output is in results/NAME/slurm/" \
  || bad "no task output in results/$name/slurm"

FEPS=$feps bash scripts/campaign.sh "${name}_local" "${decks[@]}" >"$tmp/local" 2>&1
python3 - "results/$name/summary.csv" "results/${name}_local/summary.csv" <<'PY' \
  && ok "the Slurm campaign's CSV is the local one's (but for the times)" || bad "the Slurm and local CSVs differ"
import csv, sys
rows = [list(csv.DictReader(open(p))) for p in sys.argv[1:]]
strip = lambda r: {k: v for k, v in r.items() if k not in ("wall_time_s",)}
assert [strip(r) for r in rows[0]] == [strip(r) for r in rows[1]], rows
assert [r["status"] for r in rows[0]] == ["ok", "ok", "failed"], rows[0]
PY

FEPS=$feps bash scripts/campaign.sh --slurm "$name" "${decks[@]}" >"$tmp/slurm2" 2>&1; st=$?
[ $st -eq 1 ] && grep -q "^skip   cube (finished)" "$tmp/slurm2" && grep -q "^skip   soil_column (finished)" "$tmp/slurm2" \
  && grep -q "^submit 1 case(s) as a Slurm job array" "$tmp/slurm2" \
  && ok "a second --slurm call submits only the case not finished" || bad "second --slurm call: $(tail -c 400 "$tmp/slurm2")"

mkdir -p "$tmp/bin"     # a PATH with what campaign.sh needs before it looks for sbatch, and no sbatch
for c in bash dirname basename mkdir nproc cat awk; do ln -s "$(command -v $c)" "$tmp/bin/$c"; done
PATH=$tmp/bin FEPS=$feps "$tmp/bin/bash" scripts/campaign.sh --slurm "$name" test/data/cube.dat >"$tmp/nosb" 2>&1; st=$?
[ $st -eq 2 ] && grep -q "no sbatch on PATH" "$tmp/nosb" && ok "--slurm without sbatch: one line, exit 2" \
  || bad "--slurm without sbatch: exit $st: $(head -c 300 "$tmp/nosb")"

echo "check_slurm: $pass passed, $fail failed"
[ $fail -eq 0 ]
