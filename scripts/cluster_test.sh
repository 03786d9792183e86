#!/usr/bin/env bash
# cluster_test.sh BUILD_DIR: texsim explore's sweep through a real Slurm (make cluster-test,
# docs/cluster.md). Installs Debian's slurm-wlm and munge if missing (as root), starts a
# single-node cluster on this machine with a throw-away configuration and key (munged, slurmctld
# and slurmd on ports of their own, everything in a temporary directory), emits a sweep of 240
# points as a job array (--emit slurm), makes one task fail on purpose, submits with sbatch,
# waits, checks that --collect names the failed task and writes nothing, resubmits exactly that
# task with the written resubmit.sh, collects, and checks the merged explore.csv byte-identical to
# a local --jobs 2 sweep; then a frame batch (render --frames 6 --emit slurm) through the same
# cluster, its pictures equal to a local render's. The daemons are stopped and the directory removed at the end, on failure
# too. About a minute.
set -euo pipefail
case "${1:-}" in -h|--help|"") sed -n '2,/^set -/{/^#/s/^# \{0,1\}//p}' "$0"; exit 0;; esac
build=$(cd "$1" && pwd)
texsim=$build/texsim
[ -x "$texsim" ] || { echo "cluster-test: $texsim not built (make build)" >&2; exit 1; }

need=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || need+=("$p")
done
if [ ${#need[@]} -gt 0 ]; then
  [ "$(id -u)" -eq 0 ] || { echo "cluster-test: error: not root; run: sudo apt-get install ${need[*]}" >&2; exit 1; }
  echo "cluster-test: installing ${need[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${need[@]}" > /dev/null
fi
[ "$(id -u)" -eq 0 ] || { echo "cluster-test: error: the daemons run as root here (run as root)" >&2; exit 1; }

t=$(mktemp -d /tmp/texsim-cluster-XXXXXX)
chmod 755 "$t"
export SLURM_CONF=$t/slurm.conf
stop() {
  scancel --quiet --full -u root 2>/dev/null || true
  for pid in "$t"/slurmd.pid "$t"/slurmctld.pid "$t"/munged.pid; do
    [ -s "$pid" ] && kill "$(cat "$pid")" 2>/dev/null || true
  done
  sleep 1
  for pid in "$t"/slurmd.pid "$t"/slurmctld.pid "$t"/munged.pid; do
    [ -s "$pid" ] && kill -9 "$(cat "$pid")" 2>/dev/null || true
  done
  rm -rf "$t"
}
trap stop EXIT
fail() { echo "cluster-test: FAIL: $*" >&2; for f in "$t"/slurmctld.log "$t"/slurmd.log; do [ -f "$f" ] && tail -5 "$f" >&2; done; exit 1; }

# munge: a key of our own, on a socket of our own.
mkdir -p "$t/munge"
chmod 700 "$t/munge"
mungekey --create --keyfile="$t/munge/munge.key" > /dev/null 2>&1 || dd if=/dev/urandom of="$t/munge/munge.key" bs=1024 count=1 2>/dev/null
chmod 600 "$t/munge/munge.key"
munged --force --key-file="$t/munge/munge.key" --socket="$t/munge/munge.socket" --pid-file="$t/munged.pid" \
  --log-file="$t/munge/munged.log" --seed-file="$t/munge/munged.seed"
host=$(hostname -s)
cpus=$(nproc)
mem=$(awk '/MemTotal/ { print int($2 / 1024 / 2) }' /proc/meminfo)
mkdir -p "$t/state" "$t/spool"
cat > "$SLURM_CONF" <<EOF
ClusterName=texsim-test
SlurmctldHost=$host
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$t/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$t/state
SlurmdSpoolDir=$t/spool
SlurmctldPidFile=$t/slurmctld.pid
SlurmdPidFile=$t/slurmd.pid
SlurmctldLogFile=$t/slurmctld.log
SlurmdLogFile=$t/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
MaxArraySize=10001
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 60); do
  state=$(sinfo -h -o %T 2>/dev/null | head -1 || true)
  [ "$state" = idle ] && break
  sleep 1
done
[ "$state" = idle ] || fail "the node is not idle after 60 s (sinfo: '${state:-nothing}')"
echo "cluster-test: Slurm $(sinfo -V | cut -d' ' -f2) up: one node ($host, $cpus CPUs), partition test"

# The sweep: 240 points (2 scenes x 2 orders x 2 blocks x 3 cache sizes = 24 tasks of 10 points).
sweep=(explore --scene plane,panel --order scanline,tiled --width 96 --height 64 --texture testcard:256x256
       --block 4x4,8x8 --cache-kib 2,4,8 --mem-latency 30,100,300,1000,3000 --fifo-depth 64,max --no-plots)
cd "$t"
"$texsim" "${sweep[@]}" --store "$t/local-store" -o "$t/local" --jobs 2 > /dev/null
"$texsim" "${sweep[@]}" --store "$t/store" --emit slurm "$t/sweep" --throttle 8
points=$(($(wc -l < "$t/local/explore.csv") - 1))
[ "$points" -ge 200 ] || fail "the sweep has $points points, fewer than 200"
tasks=$(wc -l < "$t/sweep/commands.txt")
broken=$((tasks / 2))
cp "$t/sweep/commands.txt" "$t/commands.kept"
sed -i "$((broken + 1))s|.*|echo 'cluster-test: task $broken fails on purpose' >\&2; exit 7|" "$t/sweep/commands.txt"
sbatch --wait --quiet "$t/sweep/sweep.sbatch" > /dev/null && fail "sbatch --wait succeeded with a failing task"
echo "cluster-test: the array of $tasks tasks ran (task $broken failing on purpose)"
if "$texsim" explore --collect "$t/sweep" --no-plots 2> "$t/collect.err"; then fail "--collect succeeded with a task missing"; fi
grep -q "task $broken ([0-9]* points missing): failed, exit code 7: cluster-test: task $broken fails on purpose" "$t/collect.err" ||
  { cat "$t/collect.err" >&2; fail "--collect did not name task $broken with its exit code and log"; }
[ ! -e "$t/sweep/explore.csv" ] || fail "--collect wrote explore.csv with a task missing"
grep -q "sbatch --array=$broken " "$t/sweep/resubmit.sh" || fail "resubmit.sh is not task $broken alone: $(cat "$t/sweep/resubmit.sh")"
cp "$t/commands.kept" "$t/sweep/commands.txt"
"$t/sweep/resubmit.sh" --wait --quiet > /dev/null || fail "the resubmitted task failed: $(tail -3 "$t/sweep/logs/task-$broken.log")"
"$texsim" explore --collect "$t/sweep" --no-plots
cmp "$t/sweep/explore.csv" "$t/local/explore.csv" || fail "the collected explore.csv differs from the local --jobs 2 sweep's"
# A frame batch: 6 frames of the plane scene, 2 a task, through the same Slurm.
"$texsim" render --scene plane --width 96 --height 64 --frames 6 -o "$t/frame.png" > /dev/null
"$texsim" render --scene plane --width 96 --height 64 --frames 6 -o "$t/frame.png" --emit slurm "$t/frames" --frames-per-task 2 --store "$t/store" > /dev/null
sbatch --wait --quiet "$t/frames/sweep.sbatch" > /dev/null || fail "the frame batch's array failed"
"$texsim" render --collect "$t/frames" > /dev/null
for f in 0 1 2 3 4 5; do
  cmp "$t/frames/frames/frame_00$f.png" "$t/frame_00$f.png" || fail "frame $f of the Slurm batch differs from the local render's"
done
echo "cluster-test: a batch of 6 frames in 3 array tasks collected, every picture the local render's"
echo "cluster-test: PASS: $points points in $tasks Slurm array tasks; task $broken failed, named by --collect and resubmitted alone; explore.csv byte-identical to a local --jobs 2 sweep"
