#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for the tests of `examples/batch.sbatch`
# (Debian 12's slurmctld and slurmd 22.05, installed by `scripts/setup.sh --tests`, run as root
# without systemd or munge):
#   scripts/slurm.sh start DIR   write DIR/slurm.conf, start both daemons with their state and
#                                logs in DIR, wait until the node takes jobs; use it with
#                                SLURM_CONF=DIR/slurm.conf
#   scripts/slurm.sh stop DIR    stop the daemons started in DIR
set -euo pipefail
cmd="${1:-}"
case "$cmd" in
start)
    dir="$(mkdir -p "$2" && cd "$2" && pwd)"
    host="$(hostname -s)"
    mkdir -p "$dir/state" "$dir/spool" "$dir/log"
    cat >"$dir/slurm.conf" <<CONF
ClusterName=physvid
SlurmctldHost=$host
AuthType=auth/none
CredType=cred/none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmUser=root
SlurmdUser=root
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmdSpoolDir=$dir/spool
StateSaveLocation=$dir/state
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
    export SLURM_CONF="$dir/slurm.conf"
    slurmctld
    slurmd
    for _ in $(seq 1 100); do
        if sinfo -h -o %t 2>/dev/null | grep -qx idle; then
            exit 0
        fi
        sleep 0.2
    done
    echo "slurm.sh: the node did not become idle in 20 s (logs in $dir/log)" >&2
    exit 1
    ;;
stop)
    dir="$2"
    pids=""
    for daemon in slurmd slurmctld; do
        if [ -f "$dir/$daemon.pid" ]; then
            pid="$(cat "$dir/$daemon.pid")"
            kill "$pid" 2>/dev/null && pids="$pids $pid"
        fi
    done
    # Gone before the next cluster takes their ports.
    for _ in $(seq 1 100); do
        alive=""
        for pid in $pids; do kill -0 "$pid" 2>/dev/null && alive=1; done
        [ -z "$alive" ] && exit 0
        sleep 0.1
    done
    ;;
*)
    echo "usage: scripts/slurm.sh start DIR | stop DIR" >&2
    exit 2
    ;;
esac
