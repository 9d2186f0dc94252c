# Sourced (sh): start_slurm_cluster DIR starts a single-node Slurm cluster on 127.0.0.1 as
# children of this shell (munged with a key it generates, slurmctld -D, slurmd -D; state, spool,
# sockets and logs under DIR), exports SLURM_CONF and waits for the node to be idle.
# stop_slurm_cluster kills those daemons by process id. No systemd, no cgroups: linuxproc
# process tracking and no task plugin. Needs root (SlurmUser/SlurmdUser root) like the tests.
slurm_pids=""

start_slurm_cluster() {
  dir=$1
  mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
  chmod 755 "$dir/munge"
  host=$(hostname -s)
  # Ports from the process id, so concurrent runs (other worktrees) do not collide.
  base=$((20000 + ($$ % 20000)))
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 2>/dev/null
  chmod 400 "$dir/munge/munge.key"
  munged -F --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
    --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed" &
  slurm_pids="$slurm_pids $!"
  cat > "$dir/slurm.conf" <<CONF
ClusterName=wangscape-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$base
SlurmdPort=$((base + 1))
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/backfill
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ReturnToService=2
MinJobAge=30
MailProg=/bin/true
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=batch Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$dir/slurm.conf"
  i=0
  while [ ! -S "$dir/munge/munge.socket" ] && [ $i -lt 50 ]; do sleep 0.1; i=$((i + 1)); done
  slurmctld -D -i -f "$SLURM_CONF" > "$dir/slurmctld.out" 2>&1 &
  slurm_pids="$slurm_pids $!"
  slurmd -D -f "$SLURM_CONF" -N "$host" > "$dir/slurmd.out" 2>&1 &
  slurm_pids="$slurm_pids $!"
  i=0
  until sinfo -h -o %t 2>/dev/null | grep -q idle; do
    i=$((i + 1))
    if [ $i -gt 150 ]; then
      echo "slurm cluster did not come up; logs:" >&2
      tail -n 20 "$dir/slurmctld.log" "$dir/slurmd.log" "$dir/slurmctld.out" "$dir/slurmd.out" >&2
      return 1
    fi
    sleep 0.1
  done
}

stop_slurm_cluster() {
  for pid in $slurm_pids; do kill "$pid" 2>/dev/null; done
  for pid in $slurm_pids; do wait "$pid" 2>/dev/null; done
  slurm_pids=""
}
