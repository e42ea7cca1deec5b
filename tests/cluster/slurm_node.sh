#!/usr/bin/env bash
# A single-node Slurm cluster in a folder, for the tests (Debian's slurmctld, slurmd and
# munge; no cgroups, no systemd, no accounting). Sourced:
#   slurm_start DIR     starts munged, slurmctld and slurmd with their state, sockets
#                       and logs in DIR, exports SLURM_CONF, and waits for the node
#   slurm_stop          stops all three (also run on exit)
#   slurm_wait JOB...   waits until the jobs have left the queue
slurm_pids=()

slurm_stop() {
  local p
  for p in "${slurm_pids[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${slurm_pids[@]}"; do wait "$p" 2>/dev/null; done
  slurm_pids=()
}

slurm_start() {
  local d=$1 host cpus port
  mkdir -p "$d/state" "$d/spool" "$d/munge"
  chmod 755 "$d/munge"
  host=$(hostname -s)
  cpus=$(nproc)
  # Ports away from the defaults (6817/6818), so a real Slurm on the machine is untouched.
  port=$((20000 + ($$ % 20000)))
  mungekey --create --keyfile="$d/munge/munge.key" 2>/dev/null ||
    dd if=/dev/urandom of="$d/munge/munge.key" bs=1024 count=1 status=none
  chmod 400 "$d/munge/munge.key"
  munged --force --foreground --key-file="$d/munge/munge.key" --socket="$d/munge/munge.socket" \
    --pid-file="$d/munge/munged.pid" --log-file="$d/munge/munged.log" --seed-file="$d/munge/munge.seed" \
    >"$d/munge/munged.out" 2>&1 &
  slurm_pids+=($!)
  cat >"$d/slurm.conf" <<CONF
ClusterName=vkraycast-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=$(id -un)
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$d/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdTimeout=30
InactiveLimit=0
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF=$d/slurm.conf
  for _ in $(seq 50); do [[ -S $d/munge/munge.socket ]] && break; sleep 0.1; done
  slurmctld -D -i -f "$SLURM_CONF" >"$d/slurmctld.out" 2>&1 &
  slurm_pids+=($!)
  slurmd -D -f "$SLURM_CONF" >"$d/slurmd.out" 2>&1 &
  slurm_pids+=($!)
  trap slurm_stop EXIT
  local state=
  for _ in $(seq 300); do
    state=$(sinfo -h -o %T 2>/dev/null | head -1)
    [[ $state == idle ]] && return 0
    sleep 0.1
  done
  echo "slurm: the node did not come up (state '$state'); logs in $d" >&2
  tail -5 "$d/slurmctld.log" "$d/slurmd.log" "$d/munge/munged.log" >&2 2>/dev/null
  return 1
}

slurm_wait() {
  local j
  for j in "$@"; do
    for _ in $(seq 1200); do
      [[ -z $(squeue -h -j "$j" 2>/dev/null) ]] && break
      sleep 0.25
    done
  done
}
