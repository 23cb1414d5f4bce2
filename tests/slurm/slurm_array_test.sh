#!/usr/bin/env bash
# The Slurm job array on a real single-node cluster: munged, slurmctld and slurmd from Debian's
# packages (slurm-wlm, munge), started here as root on a private folder and stopped at the end.
# It renders a small sequence, densifies it once as a single lidar_sgm_batch process, then as
# scripts/slurm/densify_array.sbatch submitted with sbatch --array --wait, and checks that the
# array wrote the same clouds byte for byte, every frame exactly once, a manifest per shard; then
# that a re-submission redoes only a removed frame, and that an array with a step is refused.
#
#   slurm_array_test.sh LIDAR_SGM_BATCH LIDAR_SGM_SYNTH DENSIFY_ARRAY_SBATCH
#
# Without root, slurm-wlm or munge it fails with the reason; LIDAR_SGM_SKIP_SLURM_TEST=1 skips it
# instead (exit code 77, ctest's SKIP_RETURN_CODE).
set -euo pipefail

readonly FRAMES=6
readonly TASKS=3
readonly START_TIMEOUT_S=30
readonly JOB_TIMEOUT_S=120

say() { echo "slurm_array_test: $*"; }
failure=""
die() {
  failure="$*"
  echo "slurm_array_test: FAILED: $failure" >&2
  exit 1
}

if [ "${LIDAR_SGM_SKIP_SLURM_TEST:-}" = "1" ]; then
  say "skipped: LIDAR_SGM_SKIP_SLURM_TEST=1"
  exit 77
fi
[ $# -eq 3 ] || die "usage: $0 LIDAR_SGM_BATCH LIDAR_SGM_SYNTH DENSIFY_ARRAY_SBATCH"
batch_tool="$(realpath "$1")"
synth_tool="$(realpath "$2")"
sbatch_script="$(realpath "$3")"
for f in "$batch_tool" "$synth_tool"; do [ -x "$f" ] || die "'$f' is not an executable"; done
[ -r "$sbatch_script" ] || die "'$sbatch_script' is not readable"

# The daemons run as root here (SlurmUser=root, munged as root): a cluster under another user
# would need that user to exist and to own every folder below.
[ "$(id -u)" -eq 0 ] ||
  die "needs root to run slurmctld, slurmd and munged (set LIDAR_SGM_SKIP_SLURM_TEST=1 to skip)"
# The daemons live in sbin, which a non-login shell's PATH may lack. A test run inside a Slurm job
# (or with SBATCH_* defaults set) must not hand that cluster's settings to this one's commands.
export PATH="$PATH:/usr/sbin:/sbin"
for variable in $(compgen -e | grep -E '^(SLURM|SBATCH|SALLOC|SRUN|SQUEUE|SINFO)_' || true); do
  unset "$variable"
done
missing=()
for program in munged munge unmunge slurmctld slurmd sbatch sinfo squeue scancel scontrol; do
  command -v "$program" > /dev/null || missing+=("$program")
done
[ ${#missing[@]} -eq 0 ] || die "${missing[*]} not found: install Debian's slurm-wlm and munge" \
  "(scripts/install_deps.sh), or set LIDAR_SGM_SKIP_SLURM_TEST=1 to skip"

tmp="$(mktemp -d "${TMPDIR:-/tmp}/lidar_sgm_slurm.XXXXXX")"
# munged wants its socket's folders searchable by all (clients connect) and writable by none but us.
chmod 711 "$tmp"
daemon_pids=()

# Everything started here is stopped here, on success and on failure: the jobs first (a job's
# slurmstepd outlives slurmd), then the daemons, whose exit is waited for before the folder goes.
cleanup() {
  local rc=$?
  set +e
  if [ -n "${SLURM_CONF:-}" ] && [ -e "$tmp/slurmctld.pid" ]; then
    timeout 10 scancel --quiet --user="$(id -un)" 2> /dev/null
    for _ in $(seq 50); do
      [ -z "$(timeout 5 squeue -h -o %i 2> /dev/null)" ] && break
      sleep 0.2
    done
  fi
  local i
  for ((i = ${#daemon_pids[@]} - 1; i >= 0; i--)); do
    kill -TERM "${daemon_pids[i]}" 2> /dev/null
    for _ in $(seq 50); do
      kill -0 "${daemon_pids[i]}" 2> /dev/null || break
      sleep 0.2
    done
    kill -KILL "${daemon_pids[i]}" 2> /dev/null
    wait "${daemon_pids[i]}" 2> /dev/null
  done
  if [ $rc -ne 0 ] && [ $rc -ne 77 ]; then
    for log in "$tmp"/*.log "$tmp"/*.stderr "$tmp"/jobs/*.out "$tmp"/lidar_sgm_densify-*.out; do
      [ -f "$log" ] || continue
      echo "----- $log (last 40 lines)" >&2
      tail -n 40 "$log" >&2
    done
    # Again below the logs, where a reader of the test's output looks first.
    [ -z "$failure" ] || echo "slurm_array_test: FAILED: $failure" >&2
  fi
  rm -rf "$tmp"
  exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# A TCP port that nothing listens on or uses now (/proc/net/tcp*: the local port is the hex after
# the address's colon), chosen at random so that tests side by side do not collide.
used_ports() {
  local _ local_address
  cat /proc/net/tcp /proc/net/tcp6 2> /dev/null | while read -r _ local_address _; do
    [[ "$local_address" == *:* ]] && echo $((16#${local_address##*:}))
  done
}
free_port() {
  local port
  for _ in $(seq 100); do
    port=$((20000 + RANDOM % 40000))
    if ! used_ports | grep -qx "$port" && [ "$port" != "${1:-}" ]; then
      echo "$port"
      return 0
    fi
  done
  die "no free TCP port found"
}

# Waits up to START_TIMEOUT_S for the command to succeed while the daemon PID runs.
wait_for() {
  local what="$1" pid="$2"
  shift 2
  local deadline=$((SECONDS + START_TIMEOUT_S))
  until "$@" > /dev/null 2>&1; do
    kill -0 "$pid" 2> /dev/null || die "$what: the daemon exited"
    [ $SECONDS -lt $deadline ] || die "$what: not ready after $START_TIMEOUT_S s"
    sleep 0.2
  done
}

# --- munged: its own key, socket, pid, log and seed files, so that a system munged (if any) is
# neither used nor disturbed.
mkdir -m 711 "$tmp/munge"
mkdir -m 700 "$tmp/munge-key"
head -c 1024 /dev/urandom > "$tmp/munge-key/munge.key"
chmod 400 "$tmp/munge-key/munge.key"
socket="$tmp/munge/munge.socket"
munged --foreground --socket="$socket" --key-file="$tmp/munge-key/munge.key" --pid-file="$tmp/munge/munged.pid" \
  --log-file="$tmp/munged.log" --seed-file="$tmp/munge-key/munged.seed" > "$tmp/munged.stderr" 2>&1 &
daemon_pids+=($!)
munge_round_trip() { munge -n -S "$socket" | unmunge -S "$socket"; }
wait_for "munged (log: $tmp/munged.log)" "${daemon_pids[-1]}" munge_round_trip
say "munged up"

# --- slurm.conf: this machine as the only node, with its real CPUs and memory.
host="$(hostname -s)"
node_line="$(slurmd -C | head -n 1)"
[[ "$node_line" == NodeName=* ]] || die "slurmd -C printed '$node_line', not a NodeName line"
node_line="$(sed -E "s/^NodeName=[^ ]+/NodeName=$host NodeAddr=127.0.0.1/" <<< "$node_line")"
ctld_port="$(free_port)"
slurmd_port="$(free_port "$ctld_port")"
mkdir -m 700 "$tmp/state" "$tmp/spool" "$tmp/jobs"
export SLURM_CONF="$tmp/slurm.conf"
cat > "$SLURM_CONF" << CONF
# Generated by slurm_array_test.sh: a private single-node cluster.
ClusterName=lidarsgmtest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
ReturnToService=2
# sbatch --wait polls after 2 s, then 8 s, then 32 s, the step growing only while it is under
# MinJobAge/2 (so that a finished job is seen before it is purged): 5 keeps it polling every 2 s,
# a few seconds an array instead of 10 to 42, and finished tasks stay listed for 5 s > 2 s.
MinJobAge=5
MailProg=/bin/true
$node_line State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF

# In the foreground (-D) so that their ids are ours to stop; what they print before their log file
# opens (a bad slurm.conf) goes to *.stderr.
slurmctld -D -f "$SLURM_CONF" > "$tmp/slurmctld.stderr" 2>&1 &
daemon_pids+=($!)
wait_for "slurmctld (log: $tmp/slurmctld.log)" "${daemon_pids[-1]}" scontrol ping
slurmd -D -f "$SLURM_CONF" -N "$host" > "$tmp/slurmd.stderr" 2>&1 &
daemon_pids+=($!)
node_idle() { [ "$(sinfo -h -N -n "$host" -o %t)" = "idle" ]; }
wait_for "slurmd: node $host idle in sinfo (logs: $tmp/slurmd.log, $tmp/slurmctld.log)" "${daemon_pids[-1]}" node_idle
say "cluster up: node $host idle, slurmctld port $ctld_port, slurmd port $slurmd_port"

# --- the sequence, densified once by a single process: the reference.
"$synth_tool" -out "$tmp/seq" -n "$FRAMES" -width 248 -height 75 > /dev/null
"$batch_tool" -input_dir "$tmp/seq" -output_dir "$tmp/out1" > "$tmp/single.log" 2>&1 ||
  die "the single-process run failed: $(cat "$tmp/single.log")"
frames=()
for cloud in "$tmp"/out1/*.pcd; do
  [ -f "$cloud" ] && frames+=("$(basename "$cloud" .pcd)")
done
[ ${#frames[@]} -eq "$FRAMES" ] || die "the single-process run wrote ${#frames[@]} clouds, not $FRAMES"

# Submits the array (--array=$1, then sbatch options) over the sequence into OUT2 and waits for it;
# sbatch --wait exits non-zero when a task failed. Tasks run in $tmp, the submit folder.
submit() {
  local array="$1"
  shift
  LIDAR_SGM_BATCH="$batch_tool" timeout "$JOB_TIMEOUT_S" sbatch --wait --quiet --array="$array" "$@" \
    --chdir="$tmp" "$sbatch_script" -input_dir "$tmp/seq" -output_dir "$tmp/out2"
}
# One CPU a task and the logs in jobs/, so that the first array fits a single-core runner too.
one_cpu=(--cpus-per-task=1 --output="$tmp/jobs/%A_%a.out")

# Checks that OUT2 holds exactly OUT1's clouds, byte for byte, and no temporary file.
check_clouds() {
  local frame
  for frame in "${frames[@]}"; do
    [ -f "$tmp/out2/$frame.pcd" ] || die "$1: frame $frame has no cloud in the array's output"
    cmp "$tmp/out1/$frame.pcd" "$tmp/out2/$frame.pcd" ||
      die "$1: frame $frame's cloud differs from the single-process run's"
  done
  local clouds
  # The shards' lock files (.lidar_sgm_batch*.lock) stay: removing one would race with its next taker.
  clouds="$(find "$tmp/out2" -type f ! -name 'manifest.*.jsonl' ! -name cloud_options.txt \
    ! -name '.lidar_sgm_batch*.lock' | wc -l)"
  [ "$clouds" -eq "$FRAMES" ] || die "$1: the array's output holds $clouds files besides the manifests, cloud_options.txt and the locks," \
    "not $FRAMES clouds: $(ls -A "$tmp/out2")"
}

# Prints "frame status" for every record of the shards' manifests (one JSON object a line).
manifest_records() {
  local k
  for ((k = 0; k < TASKS; k++)); do
    local manifest="$tmp/out2/manifest.shard-$k-of-$TASKS.jsonl"
    [ -f "$manifest" ] || die "shard $k/$TASKS wrote no manifest ($manifest)"
    sed -E 's/.*"frame": *"([^"]*)".*"status": *"([^"]*)".*/\1 \2/' "$manifest"
  done
}

start=$SECONDS
submit "0-$((TASKS - 1))" "${one_cpu[@]}" || die "the array failed (sbatch --wait exit code $?)"
say "array of $TASKS tasks done in $((SECONDS - start)) s"
check_clouds "array"
# Every frame exactly once over the shards, each densified.
records="$(manifest_records | sort)"
expected="$(printf '%s ok\n' "${frames[@]}" | sort)"
[ "$records" = "$expected" ] || die "the manifests do not list every frame once as ok:" \
  "got [$records], expected [$expected]"
say "${#frames[@]} clouds byte-identical to the single-process run, every frame once in $TASKS manifests"

# A re-submission after a lost frame: only that frame is redone, the same bytes again. With the
# script's own #SBATCH defaults (2 CPUs a task, logs in the submit folder) where the node has 2 CPUs.
lost="${frames[1]}"
rm "$tmp/out2/$lost.pcd"
node_cpus="$(sed -E 's/.*CPUs=([0-9]+).*/\1/' <<< "$node_line")"
if [ "$node_cpus" -ge 2 ]; then defaults=(); else defaults=("${one_cpu[@]}"); fi
submit "0-$((TASKS - 1))" "${defaults[@]}" || die "the re-submitted array failed (sbatch --wait exit code $?)"
if [ "$node_cpus" -ge 2 ]; then
  for ((k = 0; k < TASKS; k++)); do
    compgen -G "$tmp/lidar_sgm_densify-*_$k.out" > /dev/null ||
      die "task $k of the array with the script's defaults left no lidar_sgm_densify-<job>_$k.out in the submit folder"
  done
fi
check_clouds "re-submitted array"
records="$(manifest_records | sort)"
expected="$( (printf '%s skipped\n' "${frames[@]}" | grep -v "^$lost "; echo "$lost ok") | sort)"
[ "$records" = "$expected" ] || die "the re-submitted array's manifests are not 'only $lost redone':" \
  "got [$records], expected [$expected]"
say "re-submission redid only frame $lost, byte-identical"

# An array with a step has task ids that are not 0..N-1 shards: every task refuses to run.
if submit "0-4:2" "${one_cpu[@]}" 2> /dev/null; then die "an array with a step (--array=0-4:2) was not refused"; fi
grep -q "not 3 consecutive ids" "$tmp"/jobs/*_4.out || die "the array with a step failed without saying why"
say "an array with a step is refused"
say "PASSED"
