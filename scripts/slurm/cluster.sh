#!/usr/bin/env bash
# A private one-node Slurm cluster on this machine, for tests/slurm/ (Debian's slurmctld, slurmd,
# slurm-client and munge; no systemd): munged, slurmctld and slurmd started directly as root with a
# configuration of their own under DIR, on loopback and private ports, so that nothing else on the
# machine (its host name, another Slurm, another test) matters.
#
#   scripts/slurm/cluster.sh start DIR   # prints "export SLURM_CONF=DIR/slurm.conf" once the node is idle
#   scripts/slurm/cluster.sh stop DIR    # stops the daemons by their pid files and waits until they are gone
#
# start stops whatever an earlier start left in DIR first and starts from clean state (old state files
# confuse a changed configuration). Ports: IMPACTBENCH_SLURM_PORT (default 16817) and the next one.
set -euo pipefail
usage="usage: scripts/slurm/cluster.sh start|stop DIR"
action=${1:?$usage}
dir=${2:?$usage}
port=${IMPACTBENCH_SLURM_PORT:-16817}

stop_daemons() {
  local pids=() pid_file pid
  for pid_file in "$dir/slurmd.pid" "$dir/slurmctld.pid" "$dir/munged.pid"; do
    [[ -s $pid_file ]] || continue
    pid=$(cat "$pid_file")
    kill -0 "$pid" 2>/dev/null && kill "$pid" && pids+=("$pid")
  done
  # slurmctld saves its state before it ends (about 1.7 s); wait, then make sure
  for _ in $(seq 100); do
    local alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2>/dev/null && alive=1; done
    ((alive)) || return 0
    sleep 0.1
  done
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
}

case $action in
  stop) stop_daemons; exit 0 ;;
  start) ;;
  *) echo "cluster.sh: $action: $usage" >&2; exit 2 ;;
esac

[[ $(id -u) -eq 0 ]] || { echo "cluster.sh: the daemons run as root (SlurmUser=root); run as root" >&2; exit 2; }
for tool in munged slurmctld slurmd sinfo sbatch; do
  command -v "$tool" >/dev/null || { echo "cluster.sh: $tool missing: scripts/install-deps.sh --tests installs slurmctld slurmd slurm-client munge" >&2; exit 2; }
done
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
stop_daemons
rm -rf "$dir/munge" "$dir/state" "$dir/spool" "$dir"/*.log "$dir"/*.pid
mkdir -p "$dir/munge" "$dir/state" "$dir/spool"

# munge: its own key, socket, pid, log and seed; it insists on a private key and folders of its owner
dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 status=none
chmod 700 "$dir/munge"
chmod 400 "$dir/munge/munge.key"
munged --force -S "$dir/munge/munge.socket" --key-file "$dir/munge/munge.key" --pid-file "$dir/munged.pid" \
       --log-file "$dir/munged.log" --seed-file "$dir/munge/munged.seed"

# the node as slurmd -C sees it (CPUs, sockets, cores, memory), named "ci" on loopback
node=$(slurmd -C | head -1 | sed -e 's/^NodeName=[^ ]*//')
cat > "$dir/slurm.conf" <<CONF
ClusterName=impactbench
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
SchedulerParameters=sched_interval=1
# sbatch --wait polls the job every 2 s, then 8 s, then 32 s, unless MinJobAge/2 is no longer than the
# poll (so that a finished job is still on record when it looks): at 4 s it keeps polling every 2 s, and a
# wait ends within 2 s of the job instead of up to 30 s after it
MinJobAge=4
KillWait=5
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
NodeName=ci NodeHostname=localhost NodeAddr=127.0.0.1$node
PartitionName=ci Nodes=ci Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$dir/slurm.conf
slurmctld -i
slurmd -N ci
for _ in $(seq 300); do
  [[ $(sinfo -h -N -o %t 2>/dev/null) == idle ]] && { echo "export SLURM_CONF=$SLURM_CONF"; exit 0; }
  sleep 0.1
done
echo "cluster.sh: the node did not become idle within 30 s; the logs: $dir/slurmctld.log, $dir/slurmd.log" >&2
tail -n 5 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
stop_daemons
exit 1
