#!/usr/bin/env bash
# A Slurm "cluster" of this one machine, for trying and testing `scripts/campaign.sh --slurm`
# without a cluster: installs Debian's slurm-wlm and munge if they are missing, writes a minimal
# configuration in DIR (default /tmp/feps-slurm: one node, localhost, with every core; one
# partition, feps), and starts munged, slurmctld and slurmd from it, all as root.
#
#   bash scripts/slurm_localhost.sh start [DIR]    # then: export SLURM_CONF=DIR/slurm.conf
#   bash scripts/slurm_localhost.sh stop [DIR]
#
# start waits until the node is idle (at most 60 s) and prints the export line; it stops what an
# earlier start in DIR left running first. Nothing outside DIR is written but the packages.
# Exit status: 0 started or stopped; 1 the daemons did not come up (their logs are in DIR/log).
set -euo pipefail
action=${1:-}
dir=${2:-/tmp/feps-slurm}
case $action in start|stop) ;; *) echo "usage: bash scripts/slurm_localhost.sh start|stop [DIR]" >&2; exit 2 ;; esac

stop() {
    for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munge/munged.pid"; do
        if [[ -f $pidfile ]]; then
            kill "$(cat "$pidfile")" 2>/dev/null || true
            rm -f "$pidfile"
        fi
    done
    sleep 1
}

if [[ $action == stop ]]; then
    stop
    echo "slurm_localhost: stopped ($dir)"
    exit 0
fi

missing=()
for p in slurm-wlm munge; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
    SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

stop
mkdir -p "$dir/spool" "$dir/state" "$dir/log" "$dir/munge"
chmod 700 "$dir/munge"
# munge signs Slurm's messages; its key comes with the package
munged --force --socket="$dir/munge/munge.socket" --pid-file="$dir/munge/munged.pid" \
    --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed"
cat >"$dir/slurm.conf" <<EOF
# written by scripts/slurm_localhost.sh: one node (this machine), one partition
ClusterName=feps
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
NodeName=localhost CPUs=$(nproc) State=UNKNOWN
PartitionName=feps Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$dir/slurm.conf"
slurmd -f "$dir/slurm.conf"
for _ in $(seq 60); do
    if SLURM_CONF=$dir/slurm.conf sinfo -h -o %t 2>/dev/null | grep -q '^idle'; then
        echo "slurm_localhost: up; export SLURM_CONF=$dir/slurm.conf"
        exit 0
    fi
    sleep 1
done
echo "slurm_localhost: the node did not become idle in 60 s (logs in $dir/log)" >&2
exit 1
