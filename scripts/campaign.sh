#!/usr/bin/env bash
# Run a campaign of feps decks in parallel and gather one CSV.
#
#   scripts/campaign.sh [--slurm] NAME DECK...
#
# Every deck is first checked with `feps --check` (seconds each): if any fails, the campaign
# prints feps's errors and stops with exit status 2 before running anything.
# Each deck runs in results/NAME/<deck stem>/ (from the repository root) as
#   feps DECK --output <stem>.h5 > log.txt 2>&1
# as many at once as JOBS (default: the number of cores). Resumable: a case whose log.txt ends
# with the summary line 'results ...' and whose <stem>.h5 exists is not run again; any other case
# (never run, failed, interrupted) is run from the start. Then results/NAME/summary.csv gets one
# row per case (those of this call, then any other case folder of the campaign): case, status,
# exit code, wall time, steps, iterations, factorizations, cut-backs, load factor reached, every
# /summary attribute rotation_*_deg and reaction_*_f[xyz] (REPORT records), and the peak most
# tensile principal stress (MPa, over all Gauss points of the last step) of group pipe
# (PEAK_GROUP); the decks' PARAMETERS (/summary
# attributes parameter_<name>) come right after the case name, one column each.
#
# Environment:
#   FEPS        the feps executable: a path (relative or absolute) or a command on PATH (default:
#               fpm's release build of the repository, copied to results/NAME/feps so that
#               rebuilds during the campaign do not disturb it)
#   JOBS        cases at once (default: nproc); each case gets nproc / JOBS threads (at least
#               one) unless OMP_NUM_THREADS is set
#   TIMEOUT     seconds a case may run (default: no limit); a case stopped by it has status timeout
#   FEPS_ARGS   extra feps options for every case, e.g. "--method initial-stiffness"
#   PEAK_GROUP  the group whose peak principal stress goes into the CSV (default pipe)
#   RERUN=1     run every case again
#
# --slurm: run the cases on a Slurm cluster instead, as one job array (one case per task, through
# `sbatch --wait`, so the call returns when the array has ended), with the same folders, the same
# resumability and the same CSV: a second call submits only the cases not finished (failed,
# timed out, never run). The array's files are in results/NAME/slurm/ (the case list, the task
# script, one output file per task). SLURM_ARGS adds sbatch options (partition, time, memory per
# task, e.g. "--partition=long --time=02:00:00 --mem=8G"); JOBS, when set, caps the tasks that
# run at once (--array=...%JOBS). Every node must see the repository and results/ under the same
# path (a shared file system). `scripts/slurm_localhost.sh start` makes a one-node Slurm of this
# machine to try it (test/cli/check_slurm.sh runs a campaign through it).
#
# Exit status: 0 when every case of this call finished (status ok in the CSV); 1 when any of them
# failed, timed out or did not finish (the CSV is gathered all the same and the cases are named);
# 2 for bad arguments or a deck that fails feps --check (nothing is run).
set -euo pipefail

usage() { awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; }
case "${1:-}" in -h|--help) usage; exit 0 ;; esac
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# a task of a Slurm job array (--slurm below): one case, in the environment the campaign exported
if [[ ${1:-} == --run-case ]]; then
    source "$ROOT/scripts/campaign_case.sh"
    run_case "$2"
    exit 0
fi
SLURM=""
if [[ ${1:-} == --slurm ]]; then SLURM=1; shift; fi
[[ $# -ge 2 ]] || { usage >&2; exit 2; }

NAME=$1
shift
[[ $NAME =~ ^[A-Za-z0-9._-]+$ ]] || { echo "campaign: NAME must be letters, digits, . _ -" >&2; exit 2; }
CAMPAIGN=$ROOT/results/$NAME
mkdir -p "$CAMPAIGN"

# decks as absolute paths; stems must be unique (one folder per case)
declare -A seen=()
DECKS=()
for deck in "$@"; do
    [[ -f $deck ]] || { echo "campaign: no deck $deck" >&2; exit 2; }
    abs=$(cd "$(dirname "$deck")" && pwd)/$(basename "$deck")
    stem=$(basename "$deck"); stem=${stem%.*}
    [[ -z ${seen[$stem]:-} ]] || { echo "campaign: two decks named $stem ($deck, ${seen[$stem]})" >&2; exit 2; }
    seen[$stem]=$deck
    DECKS+=("$abs")
done

if [[ -z ${FEPS:-} ]]; then
    (cd "$ROOT" && fpm build --profile release > "$CAMPAIGN/build.log" 2>&1) ||
        { cat "$CAMPAIGN/build.log" >&2; echo "campaign: fpm build failed" >&2; exit 1; }
    built=$(cd "$ROOT" && fpm run --profile release --runner echo 2>/dev/null | tail -n1)
    cp "$ROOT/$built" "$CAMPAIGN/feps"
    FEPS=$CAMPAIGN/feps
fi
# a command name (no slash) is looked up on PATH; a relative path is made absolute, since every case
# runs in its own folder
[[ $FEPS == */* ]] || FEPS=$(command -v -- "$FEPS" || echo "$FEPS")
[[ -f $FEPS && -x $FEPS ]] || { echo "campaign: FEPS=$FEPS is not an executable file" >&2; exit 2; }
FEPS=$(cd "$(dirname "$FEPS")" && pwd)/$(basename "$FEPS")
JOBS_SET=${JOBS:-}
JOBS=${JOBS:-$(nproc)}
# Each case's element-loop threads: the cores shared among the cases that run at once. feps's
# own default (the cores idle when it starts) would count cases that start together as idle.
cores=$(nproc)
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-$((cores / JOBS > 0 ? cores / JOBS : 1))}
export FEPS CAMPAIGN TIMEOUT="${TIMEOUT:-}" FEPS_ARGS="${FEPS_ARGS:-}" RERUN="${RERUN:-}"
if [[ -n $SLURM ]] && ! command -v sbatch >/dev/null; then
    echo "campaign: --slurm: no sbatch on PATH (a Slurm client; to try it here: scripts/slurm_localhost.sh start)" >&2
    exit 2
fi

source "$ROOT/scripts/campaign_case.sh"
export -f run_case finished

# Check every deck first (feps --check: input, model, one factorization per stage; seconds):
# a bad deck stops the campaign before any case runs, with feps's one-line error.
nbad=0
for deck in "${DECKS[@]}"; do
    # shellcheck disable=SC2086  # FEPS_ARGS is a list of options
    if ! msg=$("$FEPS" "$deck" --check --quiet $FEPS_ARGS 2>&1); then
        echo "campaign: $msg" >&2
        nbad=$((nbad + 1))
    fi
done
[[ $nbad -eq 0 ]] || { echo "campaign: $nbad deck(s) failed feps --check; nothing was run" >&2; exit 2; }

# run_case records each case's exit code itself; xargs (or sbatch) fails only if it could not run them
xrc=0
if [[ -z $SLURM ]]; then
    printf '%s\0' "${DECKS[@]}" | xargs -0 -n 1 -P "$JOBS" bash -c 'run_case "$1"' _ || xrc=$?
else
    mkdir -p "$CAMPAIGN/slurm"
    : >"$CAMPAIGN/slurm/cases.txt"
    for deck in "${DECKS[@]}"; do
        s=$(basename "$deck"); s=${s%.*}
        if [[ -z $RERUN ]] && finished "$CAMPAIGN/$s" "$s"; then echo "skip   $s (finished)"; continue; fi
        echo "$deck" >>"$CAMPAIGN/slurm/cases.txt"
    done
    ntask=$(wc -l <"$CAMPAIGN/slurm/cases.txt")
    if ((ntask > 0)); then
        {
            echo '#!/usr/bin/env bash'
            echo "# one case of campaign $NAME: line SLURM_ARRAY_TASK_ID of cases.txt (scripts/campaign.sh --slurm)"
            printf 'exec bash %q --run-case "$(sed -n "${SLURM_ARRAY_TASK_ID}p" %q)"\n' \
                "$ROOT/scripts/campaign.sh" "$CAMPAIGN/slurm/cases.txt"
        } >"$CAMPAIGN/slurm/task.sh"
        throttle=""; [[ -n $JOBS_SET ]] && throttle="%$JOBS"
        echo "submit $ntask case(s) as a Slurm job array"
        # shellcheck disable=SC2086  # SLURM_ARGS is a list of sbatch options
        sbatch --wait --quiet --array="1-$ntask$throttle" --job-name="feps-$NAME" \
            --output="$CAMPAIGN/slurm/task_%a.out" ${SLURM_ARGS:-} "$CAMPAIGN/slurm/task.sh" || xrc=$?
    fi
fi

# ------------------------------------------------------------------------------------- gather
# the cases of this call, then those of earlier calls of the same campaign (folders with a log)
STEMS=()
for deck in "${DECKS[@]}"; do s=$(basename "$deck"); STEMS+=("${s%.*}"); done
for log in "$CAMPAIGN"/*/log.txt; do
    [[ -f $log ]] || continue
    s=$(basename "$(dirname "$log")")
    [[ -n ${seen[$s]:-} ]] || STEMS+=("$s")
done
grc=0
python3 - "$CAMPAIGN" "${PEAK_GROUP:-pipe}" "${#DECKS[@]}" "${STEMS[@]}" <<'PYTHON' || grc=$?
import csv, os, sys
import h5py
import numpy as np

campaign, peak_group, ncall, stems = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4:]
rows, rotations, parameters = [], [], []
for stem in stems:
    folder = os.path.join(campaign, stem)
    h5 = os.path.join(folder, stem + ".h5")
    log = os.path.join(folder, "log.txt")
    row = {"case": stem}
    last = ""
    if os.path.exists(log):
        with open(log, errors="replace") as fh:
            lines = [l.strip() for l in fh if l.strip()]
        last = lines[-1] if lines else ""
    code, elapsed = "", ""
    status_file = os.path.join(folder, "exit_status.txt")
    if os.path.exists(status_file):
        code, elapsed = (open(status_file).read().split() + ["", ""])[:2]
    if os.path.exists(h5) and last.startswith("results "):
        row["status"] = "ok"
        with h5py.File(h5, "r") as f:
            s = f["summary"].attrs
            row["wall_time_s"] = f"{float(s['wall_time']):.3f}"
            for key in ("steps", "iterations", "factorizations", "cutbacks"):
                row[key] = int(s[key]) if key in s else ""
            for key in sorted(s):
                if (key.startswith("rotation_") and key.endswith("_deg")) or \
                        (key.startswith("reaction_") and key[-3:] in ("_fx", "_fy", "_fz")):   # REPORT records
                    row[key] = f"{float(s[key]):.6g}"
                    if key not in rotations:
                        rotations.append(key)
                elif key.startswith("parameter_"):       # the deck's PARAMETERS records
                    v = s[key]
                    row[key[len("parameter_"):]] = v.decode() if isinstance(v, bytes) else f"{float(v):.6g}"
                    if key not in parameters:
                        parameters.append(key)
            steps = sorted(f["steps"], key=int) if "steps" in f else []   # by number: "10000" < "5000" as text
            if steps:
                row["load_factor"] = f"{float(f['steps/' + steps[-1]].attrs['load_factor']):.6g}"
                path = f"steps/{steps[-1]}/principal/{peak_group}"
                if path in f:
                    row[f"peak_tensile_{peak_group}_MPa"] = f"{float(np.max(f[path][:, 0])):.6g}"
    else:
        row["status"] = ("not run" if not os.path.exists(log) else
                         "timeout" if code == "124" else "failed" if code not in ("", "0") else "incomplete")
        row["wall_time_s"] = elapsed
        row["last_log_line"] = last[:160]
    row["exit_code"] = code
    rows.append(row)

columns = (["case"] + [p[len("parameter_"):] for p in parameters] +
           ["status", "exit_code", "wall_time_s", "steps", "iterations", "factorizations", "cutbacks",
            "load_factor"] + sorted(rotations) + [f"peak_tensile_{peak_group}_MPa", "last_log_line"])
out = os.path.join(campaign, "summary.csv")
with open(out, "w", newline="") as fh:
    writer = csv.DictWriter(fh, fieldnames=columns, restval="")
    writer.writeheader()
    writer.writerows(rows)
print(f"{out}: {sum(r['status'] == 'ok' for r in rows)} of {len(rows)} cases finished")
bad = [f"{r['case']} ({r['status']})" for r in rows[:ncall] if r["status"] != "ok"]
if bad:
    print(f"campaign: {len(bad)} of {ncall} cases not finished: {', '.join(bad)}", file=sys.stderr)
    sys.exit(1)
PYTHON
[[ $xrc -eq 0 ]] || { echo "campaign: $([[ -n $SLURM ]] && echo sbatch || echo xargs) stopped with exit status $xrc" >&2; exit 1; }
[[ $grc -eq 0 ]] || exit 1
