#!/usr/bin/env bash
# A one-node Slurm on this host, for testing `twoball sweep --slurm` against a real scheduler.
#
#   scripts/slurm_local.sh start   install slurm-wlm and munge (Debian) if missing, write a
#                                  one-node slurm.conf, start munged, slurmctld and slurmd,
#                                  wait until sinfo shows the node idle
#   scripts/slurm_local.sh stop    stop the daemons started here, by their pid files
#   scripts/slurm_local.sh env     print the SLURM_CONF line the clients need
#
# Everything lives in $TWOBALL_SLURM_DIR (default: a folder in the system's temp dir); the
# clients (sbatch, squeue, scancel, sinfo) find the cluster through SLURM_CONF. Works as root
# in a plain container without systemd (proctrack/linuxproc, task/none: no cgroups needed).
set -euo pipefail
DIR="${TWOBALL_SLURM_DIR:-${TMPDIR:-/tmp}/twoball-slurm}"
CONF="$DIR/slurm.conf"
MUNGE_SOCKET="$DIR/munge/munge.socket"
SUDO=""
if [ "$(id -u)" != 0 ] && command -v sudo >/dev/null 2>&1; then SUDO=sudo; fi

install() {
  if command -v slurmctld >/dev/null 2>&1 && command -v slurmd >/dev/null 2>&1 \
    && command -v sbatch >/dev/null 2>&1 && command -v munged >/dev/null 2>&1; then
    return
  fi
  command -v apt-get >/dev/null 2>&1 || { echo "slurm_local: no apt-get to install slurm-wlm and munge" >&2; exit 1; }
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
    slurm-wlm munge >/dev/null
}

write_conf() {
  local host node
  host="$(hostname -s)"
  # The node line as slurmd sees this machine (CPUs, sockets, cores, memory).
  node="$(slurmd -C | head -n 1)"
  mkdir -p "$DIR/state" "$DIR/spool" "$DIR/munge"
  cat >"$CONF" <<EOF
ClusterName=twoball-local
SlurmctldHost=$host
AuthType=auth/munge
AuthInfo=socket=$MUNGE_SOCKET
CredType=cred/munge
SlurmUser=$(id -un)
SlurmdUser=root
SlurmctldPort=${TWOBALL_SLURM_PORT:-6817}
SlurmdPort=$(( ${TWOBALL_SLURM_PORT:-6817} + 1 ))
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/slurmctld.log
SlurmdLogFile=$DIR/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
MinJobAge=600
$node State=UNKNOWN
PartitionName=local Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
}

running() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2>/dev/null; }

start() {
  install
  stop >/dev/null 2>&1 || true
  write_conf
  export SLURM_CONF="$CONF"
  # A key of this cluster's own (munged refuses one that others can read).
  if [ ! -s "$DIR/munge/munge.key" ]; then
    (umask 077 && dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none)
  fi
  chmod 700 "$DIR/munge"
  munged --force --socket="$MUNGE_SOCKET" --key-file="$DIR/munge/munge.key" \
    --pid-file="$DIR/munged.pid" --log-file="$DIR/munged.log" --seed-file="$DIR/munge/munged.seed"
  slurmctld -f "$CONF" -c
  slurmd -f "$CONF" -c
  local t=0
  until sinfo -h -o '%T' 2>/dev/null | grep -qx 'idle'; do
    t=$((t + 1))
    if [ "$t" -gt 60 ]; then
      echo "slurm_local: the node did not become idle within 60 s; logs in $DIR" >&2
      sinfo >&2 || true
      tail -n 20 "$DIR/slurmctld.log" "$DIR/slurmd.log" >&2 || true
      exit 1
    fi
    sleep 1
  done
  echo "slurm_local: one-node Slurm up ($(sinfo -h -o '%N %c CPUs %T')); export SLURM_CONF=$CONF"
}

stop() {
  local p
  for p in slurmd slurmctld munged; do
    local f="$DIR/$p.pid"
    if running "$f"; then
      kill "$(cat "$f")" 2>/dev/null || true
      for _ in $(seq 1 50); do running "$f" || break; sleep 0.1; done
      if running "$f"; then kill -9 "$(cat "$f")" 2>/dev/null || true; fi
    fi
    rm -f "$f"
  done
  echo "slurm_local: stopped"
}

case "${1:-}" in
  start) start ;;
  stop) stop ;;
  env) echo "SLURM_CONF=$CONF" ;;
  *) echo "usage: $0 start|stop|env" >&2; exit 2 ;;
esac
