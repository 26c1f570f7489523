#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, for the tests of `launch: slurm` (docs/cluster.md):
# munged, slurmctld and slurmd with their own configuration, keys, sockets, state and logs in one
# private folder; the system's /etc/slurm and /etc/munge are not touched.
#   scripts/local-slurm.sh start    # idempotent; prints `export SLURM_CONF=...` on its last line
#   scripts/local-slurm.sh stop
#   scripts/local-slurm.sh env      # the export line only
# Folder: $COSIM_SLURM_DIR (default /tmp/cosim-slurm-$UID). Needs slurmd, slurmctld,
# slurm-client and munge (scripts/setup.sh installs them) and root (the daemons run as root).
set -euo pipefail
dir="${COSIM_SLURM_DIR:-/tmp/cosim-slurm-$(id -u)}"
conf="$dir/slurm.conf"
host="$(hostname -s)"
cmd="${1:-start}"

die() { echo "local-slurm: $*" >&2; exit 1; }
for exe in munged slurmctld slurmd srun sinfo; do
  command -v "$exe" > /dev/null || [ -x "/usr/sbin/$exe" ] ||
    die "$exe not found: run scripts/setup.sh (it installs slurmd, slurmctld, slurm-client, munge)"
done
export PATH="$PATH:/usr/sbin"

alive() { [ -f "$1" ] && kill -0 "$(cat "$1")" 2> /dev/null; }

stop() {
  for pidfile in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    if alive "$pidfile"; then kill "$(cat "$pidfile")" 2> /dev/null || true; fi
  done
  for _ in $(seq 50); do
    alive "$dir/slurmd.pid" || alive "$dir/slurmctld.pid" || alive "$dir/munged.pid" || return 0
    sleep 0.1
  done
}

case "$cmd" in
  env) echo "export SLURM_CONF=$conf"; exit 0 ;;
  stop) stop; exit 0 ;;
  start) ;;
  *) die "unknown command '$cmd' (start, stop, env)" ;;
esac
[ "$(id -u)" = 0 ] || die "the daemons of a local cluster run as root; run it as root"

mkdir -p "$dir"/{state,spool,munge}
chmod 0700 "$dir" "$dir/munge"
if [ ! -s "$dir/munge/munge.key" ]; then
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
  chmod 0400 "$dir/munge/munge.key"
fi
cpus="$(nproc)"
mem_mb="$(awk '/MemTotal/ { print int($2 / 1024 * 0.9) }' /proc/meminfo)"
cat > "$conf.tmp" << CONF
# written by scripts/local-slurm.sh: a one-node cluster for cosim's tests
ClusterName=cosim-local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=${COSIM_SLURMCTLD_PORT:-16817}
SlurmdPort=${COSIM_SLURMD_PORT:-16818}
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdTimeout=30
NodeName=$host CPUs=$cpus RealMemory=$mem_mb State=UNKNOWN
PartitionName=local Nodes=$host Default=YES MaxTime=INFINITE OverSubscribe=FORCE:4 State=UP
CONF
mv "$conf.tmp" "$conf"
export SLURM_CONF="$conf"

alive "$dir/munged.pid" || munged --key-file="$dir/munge/munge.key" \
  --socket="$dir/munge/munge.socket" --pid-file="$dir/munged.pid" \
  --log-file="$dir/munged.log" --seed-file="$dir/munge/munge.seed" --force
alive "$dir/slurmctld.pid" || slurmctld -f "$conf"
alive "$dir/slurmd.pid" || slurmd -f "$conf"
for _ in $(seq 100); do
  if sinfo -h -o %T 2> /dev/null | grep -qE '^(idle|mixed|allocated)'; then
    echo "local-slurm: one node ($host, $cpus CPUs) up; logs in $dir"
    echo "export SLURM_CONF=$conf"
    exit 0
  fi
  sleep 0.2
done
die "the node did not come up within 20 s: see $dir/slurmctld.log and $dir/slurmd.log"
