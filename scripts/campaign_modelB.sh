#!/usr/bin/env bash
# Model B (thesis chapter 5): the 18 cases of input/modelB through scripts/campaign.sh.
#
#   scripts/campaign_modelB.sh              # all 18: SE1-3 SD1-3 FE1-3 FD1-3 PE1-3 PD1-3
#   scripts/campaign_modelB.sh SE1 FE1 ...  # only these cases
#
# Results in results/modelB/<case>/ and results/modelB/summary.csv (see campaign.sh for the
# environment: JOBS, TIMEOUT, FEPS, FEPS_ARGS, RERUN, and the exit status: 1 when a case fails).
# The decks are written by scripts/make_model_b.py.
set -euo pipefail
case "${1:-}" in
    -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
    -*) echo "campaign_modelB: unknown option $1 (see --help)" >&2; exit 2 ;;
esac
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cases=("$@")
if [[ ${#cases[@]} -eq 0 ]]; then
    cases=(SE1 SE2 SE3 SD1 SD2 SD3 FE1 FE2 FE3 FD1 FD2 FD3 PE1 PE2 PE3 PD1 PD2 PD3)
fi
decks=()
for c in "${cases[@]}"; do
    deck=$ROOT/input/modelB/$c.dat
    [[ -f $deck ]] || { echo "campaign_modelB: no deck $deck" >&2; exit 2; }
    decks+=("$deck")
done
exec "$ROOT/scripts/campaign.sh" modelB "${decks[@]}"
