#!/usr/bin/env bash
# End to end on a real one-node Slurm: starts munged, slurmctld and slurmd (as root, no systemd,
# everything private to this run: its own munge key and socket, its own ports and slurm.conf), submits
# the smoke suite as 3 shards with analysis/slurm/submit.sh, waits for the merge job, and proves the
# merged report equals an unsharded sweep of the same suite in every deterministic field (and that
# the comparison fails on a planted difference), and that the report page was rendered.
#
#   slurm_e2e.sh BSPBENCH OUT_DIR
#
# OUT_DIR is emptied first and left behind: slurm.conf, the daemons' logs, the jobs' output and the
# reports, for debugging. The daemons and anything they started are stopped on every exit.
# Exit 77 (skipped) when not root or Slurm/munge are not installed, except in CI (CI=true), where
# .ci/setup installs them and a skip would hide that this never ran.
set -euo pipefail

skip() {
  if [[ ${CI:-} == true ]]; then echo "slurm_e2e: FAIL: $* (CI must run this: .ci/setup installs Slurm)" >&2; exit 1; fi
  echo "slurm_e2e: SKIPPED: $*" >&2
  exit 77
}
die() { echo "slurm_e2e: FAIL: $*" >&2; exit 1; }
(($# == 2)) || { echo "usage: slurm_e2e.sh BSPBENCH OUT_DIR" >&2; exit 2; }
bspbench=$(realpath "$1")
out=$2
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
[[ -x $bspbench ]] || { echo "slurm_e2e: $bspbench: not an executable" >&2; exit 2; }

[[ $(id -u) -eq 0 ]] || skip "needs root (slurmd runs jobs as root here, without a slurm user)"
for tool in munged mungekey slurmctld slurmd sbatch squeue sinfo scontrol scancel; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (apt-get install slurmctld slurmd slurm-client munge)"
done

start=$SECONDS
rm -rf "$out"
mkdir -p "$out"
out=$(realpath "$out")
# One snapshot of the binary for every shard, the merge and the unsharded sweep: a rebuild while
# the test runs would otherwise mix two builds (and a shard could meet a half-written file).
mkdir -p "$out/bin"
cp "$bspbench" "$out/bin/bspbench"
bspbench=$out/bin/bspbench
"$bspbench" sweep --help >/dev/null || die "$bspbench: the copy does not run"
# Sockets live here, not in OUT_DIR: a unix socket's path is limited to 107 bytes, and munged wants
# every directory above its socket searchable by all.
run=$(mktemp -d /tmp/bspbench-slurm.XXXXXX)
chmod 755 "$run"
conf=$out/slurm.conf
export SLURM_CONF=$conf
node=$(hostname -s)
daemons=()

# Every process that carries this run's SLURM_CONF: the daemons, the job steps they forked (which
# outlive slurmd by design) and the jobs. The path is unique to this run, so nothing else matches.
ours() {
  local p
  for p in /proc/[0-9]*; do
    p=${p#/proc/}
    [[ $p == "$$" || $p == "$BASHPID" ]] && continue
    { tr '\0' '\n' <"/proc/$p/environ"; } 2>/dev/null | grep -qxF "SLURM_CONF=$conf" && echo "$p"
  done
  return 0
}

stop() {
  local status=$?
  trap - EXIT
  set +e
  if [[ -f $conf ]] && ((${#daemons[@]})); then
    scancel --full --quiet $(squeue -h -o %A 2>/dev/null) 2>/dev/null
    for _ in {1..20}; do [[ -z $(squeue -h 2>/dev/null) ]] && break; sleep 0.5; done
  fi
  ((${#daemons[@]})) && kill -TERM "${daemons[@]}" 2>/dev/null
  for _ in {1..20}; do
    alive=()
    for p in "${daemons[@]}"; do kill -0 "$p" 2>/dev/null && alive+=("$p"); done
    ((${#alive[@]})) || break
    sleep 0.5
  done
  ((${#alive[@]})) && kill -KILL "${alive[@]}" 2>/dev/null
  leftovers=$(ours)
  if [[ -n $leftovers ]]; then
    echo "slurm_e2e: killing leftover processes of this cluster: $(echo $leftovers)" >&2
    kill -KILL $leftovers 2>/dev/null
  fi
  wait 2>/dev/null
  rm -rf "$run"
  if ((status != 0)); then
    for log in "$out"/logs/*.log "$out"/sharded/logs/*.out; do
      [[ -f $log ]] && { echo "--- $log (last 15 lines)" >&2; tail -n 15 "$log" >&2; }
    done
    echo "slurm_e2e: logs and reports are in $out" >&2
  fi
  exit "$status"
}
trap stop EXIT
trap 'exit 130' INT TERM

# Two free ports, so this cluster cannot meet a real one or another run of this test on the machine.
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')

mkdir -p "$out/logs" "$run/state" "$run/spool"
mungekey --create --keyfile="$run/munge.key"
munged -F --key-file="$run/munge.key" --socket="$run/munge.socket" --pid-file="$run/munged.pid" \
  --seed-file="$run/munged.seed" 2>"$out/logs/munged.log" &
daemons+=($!)
for _ in {1..50}; do [[ -S $run/munge.socket ]] && break; sleep 0.1; done
[[ -S $run/munge.socket ]] || die "munged did not start (logs/munged.log)"

cat >"$conf" <<CONF
# A one-node cluster for tests/slurm/slurm_e2e.sh: no cgroups, no accounting, no systemd.
ClusterName=bspbench-e2e
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$run/munge.socket
StateSaveLocation=$run/state
SlurmdSpoolDir=$run/spool
SlurmctldPidFile=$run/slurmctld.pid
SlurmdPidFile=$run/slurmd.pid
SlurmctldLogFile=$out/logs/slurmctld.log
SlurmdLogFile=$out/logs/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
MailProg=/bin/true
ReturnToService=2
# A shard that fails cancels the merge job instead of leaving it pending for ever.
DependencyParameters=kill_invalid_depend
MinJobAge=600
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=e2e Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF

slurmctld -D -i -f "$conf" >"$out/logs/slurmctld.out" 2>&1 &
daemons+=($!)
slurmd -D -f "$conf" -N "$node" >"$out/logs/slurmd.out" 2>&1 &
daemons+=($!)
state=
for _ in {1..60}; do
  for p in "${daemons[@]}"; do kill -0 "$p" 2>/dev/null || die "a daemon exited (pid $p; see logs/)"; done
  state=$(sinfo -h -N -n "$node" -o %t 2>/dev/null || true)
  [[ $state == idle ]] && break
  sleep 1
done
[[ $state == idle ]] || die "node $node is not idle after 60 s (sinfo says '${state:-nothing}')"
echo "slurm_e2e: one-node Slurm $(sinfo -V | cut -d' ' -f2) up on $node in $((SECONDS - start)) s"

read -r array_id merge_id < <(BSPBENCH=$bspbench "$repo/analysis/slurm/submit.sh" --suite smoke --shards 3 --out "$out/sharded" \
  --cpus-per-task=1 --time=10)
[[ $array_id =~ ^[0-9]+$ && $merge_id =~ ^[0-9]+$ ]] || die "submit.sh printed no job ids"

# Without accounting, a finished job stays in slurmctld's memory for MinJobAge: long enough to read.
job_state() { scontrol -o show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2 | sort -u | paste -sd,; }
merge_state=
deadline=$((SECONDS + 150))
while ((SECONDS < deadline)); do
  merge_state=$(job_state "$merge_id")
  case $merge_state in
    COMPLETED) break ;;
    PENDING | RUNNING | CONFIGURING | COMPLETING | "") sleep 2 ;;
    *) die "merge job $merge_id ended $merge_state (shards: $(job_state "$array_id"))" ;;
  esac
done
[[ $merge_state == COMPLETED ]] || die "merge job $merge_id is still ${merge_state:-unknown} after 150 s (shards: $(job_state "$array_id"))"
[[ $(job_state "$array_id") == COMPLETED ]] || die "shards ended $(job_state "$array_id") yet the merge ran"
echo "slurm_e2e: 3 shards and the merge completed in $((SECONDS - start)) s"

"$bspbench" sweep --suite smoke --threads 2 --out "$out/unsharded.json" --journal-dir "$out/unsharded-journal" \
  >"$out/logs/unsharded.log" 2>&1 || die "the unsharded sweep failed (logs/unsharded.log)"
python3 - "$out/sharded/merged.json" <<'PY' || die "the merged report is not the 3 shards'"
import json, sys
shards = json.load(open(sys.argv[1]))["shards"]
assert sorted((s["index"], s["count"]) for s in shards) == [(0, 3), (1, 3), (2, 3)], shards
PY
python3 "$here/compare_reports.py" "$out/sharded/merged.json" "$out/unsharded.json" ||
  die "the merged report differs from the unsharded one"
python3 "$here/compare_reports.py" --self-check "$out/unsharded.json" || die "the comparison cannot fail"
[[ -s $out/sharded/report/index.html ]] || die "no rendered report at sharded/report/index.html"
echo "slurm_e2e: PASS in $((SECONDS - start)) s (outputs in $out)"
