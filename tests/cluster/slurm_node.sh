#!/usr/bin/env bash
# A Slurm cluster of several nodes on one machine, in a folder, for the tests (Debian's
# slurmctld, slurmd and munge; no cgroups, no systemd, no accounting). Each node is its
# own slurmd (slurmd -N NAME, its own port, spool and log: Slurm's way of running
# several daemons on one host for testing). Sourced:
#   slurm_start DIR [N] starts munged, slurmctld and N slurmd daemons (default 3, nodes
#                       n1..nN of one CPU each) with their state, sockets and logs in
#                       DIR, exports SLURM_CONF, and waits for every node
#   slurm_kill_node NODE  loses a node in the middle of its work: kills its slurmd and
#                       every process of the jobs running on it, as a crash would
#   slurm_stop          stops them all (also run on exit)
#   slurm_wait JOB...   waits until the jobs have left the queue
slurm_pids=()
declare -A slurm_node_pid

slurm_stop() {
  local p
  for p in "${slurm_pids[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${slurm_pids[@]}"; do wait "$p" 2>/dev/null; done
  slurm_pids=()
}

slurm_start() {
  local d=$1 nodes=${2:-3} host port k
  mkdir -p "$d/state" "$d/munge"
  chmod 755 "$d/munge"
  host=$(hostname -s)
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
SlurmUser=$(id -un)
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$d/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool/%n
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd-%n.pid
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd-%n.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmdTimeout=5
SlurmctldTimeout=5
MessageTimeout=5
InactiveLimit=0
KillWait=5
CONF
  local names=()
  for ((k = 1; k <= nodes; k++)); do
    echo "NodeName=n$k NodeHostname=$host NodeAddr=127.0.0.1 Port=$((port + k)) CPUs=1 State=UNKNOWN" >>"$d/slurm.conf"
    names+=("n$k")
    mkdir -p "$d/spool/n$k"
  done
  echo "PartitionName=test Nodes=n[1-$nodes] Default=YES MaxTime=INFINITE State=UP" >>"$d/slurm.conf"
  export SLURM_CONF=$d/slurm.conf
  for _ in $(seq 50); do [[ -S $d/munge/munge.socket ]] && break; sleep 0.1; done
  slurmctld -D -i -f "$SLURM_CONF" >"$d/slurmctld.out" 2>&1 &
  slurm_pids+=($!)
  for k in "${names[@]}"; do
    slurmd -D -N "$k" -f "$SLURM_CONF" >"$d/slurmd-$k.out" 2>&1 &
    slurm_pids+=($!)
    slurm_node_pid[$k]=$!
  done
  trap slurm_stop EXIT
  local idle=0
  for _ in $(seq 300); do
    idle=$(sinfo -h -N -o %T 2>/dev/null | grep -c '^idle$')
    ((idle == nodes)) && return 0
    sleep 0.1
  done
  echo "slurm: $idle of $nodes nodes came up; logs in $d" >&2
  tail -5 "$d/slurmctld.log" "$d"/slurmd-*.log "$d/munge/munged.log" >&2 2>/dev/null
  return 1
}

slurm_kill_node() {
  local node=$1 job p
  kill -9 "${slurm_node_pid[$node]}" 2>/dev/null
  wait "${slurm_node_pid[$node]}" 2>/dev/null
  # The jobs' processes outlive their slurmd (slurmstepd runs them): on a lost node they
  # die with it. Found by the job ID in their environment, and slurmstepd by its title.
  for job in $(squeue -h -w "$node" -o %A 2>/dev/null); do
    for p in /proc/[0-9]*; do
      if tr '\0' '\n' 2>/dev/null <"$p/environ" | grep -qx "SLURM_JOB_ID=$job" ||
        grep -qF "slurmstepd: [$job." "$p/cmdline" 2>/dev/null; then
        kill -9 "${p#/proc/}" 2>/dev/null
      fi
    done
  done
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
