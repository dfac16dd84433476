#!/usr/bin/env bash
# A throw-away single-node SLURM on this machine (localhost only), for the integration test.
#   local_cluster.sh start DIR   install slurm-wlm + munge if missing, write /etc/slurm/slurm.conf,
#                                start munged, slurmctld, slurmd; state and PIDs live in DIR
#   local_cluster.sh stop DIR    stop exactly the daemons started above, remove the config
# Needs root. No systemd: every daemon is started and stopped by hand (see shared/notes/local-slurm.md).
# Uses the fixed ports 6817-6818 on 127.0.0.1: only one such cluster per machine at a time.
set -euo pipefail
cmd=${1:?start|stop}
dir=$(realpath -m "${2:?state directory}")
conf=/etc/slurm/slurm.conf

start() {
  if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null
  fi
  if [ -e "$conf" ] && ! grep -q "vcor-local-cluster" "$conf"; then
    echo "refusing to overwrite an existing $conf that this script did not write" >&2
    exit 1
  fi
  mkdir -p "$dir"/{state,spool,log} /etc/slurm /run/munge
  chown munge:munge /run/munge
  [ -s /etc/munge/munge.key ] || { dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key 2>/dev/null; \
    chown munge:munge /etc/munge/munge.key; chmod 400 /etc/munge/munge.key; }
  local host cpus mem
  host=$(hostname -s)
  cpus=$(slurmd -C | sed -n 's/.*CPUs=\([0-9]*\).*/\1/p' | head -1)
  mem=$(slurmd -C | sed -n 's/.*RealMemory=\([0-9]*\).*/\1/p' | head -1)
  cat > "$conf" <<CONF
# vcor-local-cluster: written by workflow/slurm/local_cluster.sh, removed by its stop command
ClusterName=vcorlocal
SlurmctldHost=${host}(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
StateSaveLocation=${dir}/state
SlurmdSpoolDir=${dir}/spool
SlurmctldPidFile=${dir}/slurmctld.pid
SlurmdPidFile=${dir}/slurmd.pid
SlurmctldLogFile=${dir}/log/slurmctld.log
SlurmdLogFile=${dir}/log/slurmd.log
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=${dir}/log/jobcomp.log
MinJobAge=300
NodeName=${host} NodeAddr=127.0.0.1 CPUs=${cpus} RealMemory=${mem} State=UNKNOWN
PartitionName=main Nodes=${host} Default=YES MaxTime=INFINITE State=UP
CONF
  if munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
    echo "reusing the munged already running (not ours: stop leaves it)"
  else
    # munged runs as the munge user, so its PID file lives where that user can write
    runuser -u munge -- /usr/sbin/munged --pid-file=/run/munge/vcor-munged.pid --socket=/run/munge/munge.socket.2
    cp /run/munge/vcor-munged.pid "$dir/munged.pid"
  fi
  slurmctld -f "$conf"
  slurmd -f "$conf"
  for _ in $(seq 1 50); do
    if sinfo -h -o %T 2>/dev/null | grep -qE "idle|mixed|alloc"; then
      echo "local SLURM up: $(sinfo -h -o '%P %D %T %c')"
      return 0
    fi
    sleep 0.2
  done
  echo "SLURM did not come up; logs in $dir/log" >&2
  return 1
}

stop() {
  for d in slurmd slurmctld munged; do
    f="$dir/$d.pid"
    if [ -s "$f" ]; then
      pid=$(cat "$f")
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null || true
      rm -f "$f"
    fi
  done
  if [ -e "$conf" ] && grep -q "vcor-local-cluster" "$conf"; then rm -f "$conf"; fi
}

"$cmd"
