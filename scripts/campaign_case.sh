#!/usr/bin/env bash
# One case of a campaign (sourced by scripts/campaign.sh, which runs it through xargs, or as a
# task of a Slurm job array with --slurm): run_case DECK runs DECK in $CAMPAIGN/<stem>/ with
# $FEPS, $TIMEOUT, $FEPS_ARGS and $RERUN as campaign.sh describes them.

finished() {   # finished CASEDIR STEM: the log ends with the summary line and the HDF5 exists
    [[ -f $1/$2.h5 && -f $1/log.txt ]] && tail -n 1 "$1/log.txt" | grep -q '^results '
}

run_case() {
    local deck=$1 stem dir start rc ms
    stem=$(basename "$deck"); stem=${stem%.*}
    dir=$CAMPAIGN/$stem
    if [[ -z $RERUN ]] && finished "$dir" "$stem"; then
        echo "skip   $stem (finished)"
        return 0
    fi
    mkdir -p "$dir"
    rm -f "$dir/$stem.h5" "$dir/$stem.h5.part" "$dir/$stem.xmf" "$dir/exit_status.txt"
    echo "run    $stem"
    start=$(date +%s%N)
    rc=0
    # shellcheck disable=SC2086  # FEPS_ARGS is a list of options
    (cd "$dir" && if [[ -n $TIMEOUT ]]; then
         exec timeout --signal=TERM "$TIMEOUT" "$FEPS" "$deck" --output "$stem.h5" $FEPS_ARGS
     else
         exec "$FEPS" "$deck" --output "$stem.h5" $FEPS_ARGS
     fi) > "$dir/log.txt" 2>&1 || rc=$?
    # exit code and elapsed seconds, for the CSV (the HDF5 holds the wall time of a finished run)
    ms=$(( ($(date +%s%N) - start) / 1000000 ))
    printf '%s %d.%03d\n' "$rc" $((ms / 1000)) $((ms % 1000)) > "$dir/exit_status.txt"
    echo "done   $stem (exit $rc)"
}
