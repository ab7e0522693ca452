#!/usr/bin/env bash
# cluster.SlurmArrayDataset: a real single-node Slurm runs
# deploy/slurm/dataset-array.sbatch as a 4-task array on a tiny spec, and the
# merged dataset must equal an unsharded run of the same spec, file for file.
# munged, slurmctld and slurmd run as the current user on loopback, on free
# ports, from a temporary folder: no system configuration is read or written.
# Every job and daemon is stopped on exit, failed or not. Exit status 77
# (ctest: skipped, with the reason) where Slurm is missing or cannot start.
# Usage: slurm_array_test.sh FACIAL_PROGRAM SOURCE_DIR
# FACIAL_CLUSTER_TIMEOUT (seconds, default 150) bounds the wait for the jobs.
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: $0 FACIAL_PROGRAM SOURCE_DIR" >&2; exit 2; }
facial="$(realpath "$1")"
source_dir="$(realpath "$2")"
timeout_s="${FACIAL_CLUSTER_TIMEOUT:-150}"
shards=4
items=8
export PATH="$PATH:/usr/sbin:/sbin"

skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*" >&2; exit 1; }

for tool in munged mungekey slurmctld slurmd sbatch scontrol squeue scancel sinfo python3; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (Debian packages slurm-wlm and munge)"
done
[ -x "$facial" ] || fail "$facial: no such program (build the target facial_cli)"

# A scheduler around this test (ctest inside a Slurm job or a pod) must not
# leak its shard into the runs below.
while read -r name; do
  case "$name" in
    SLURM_* | SBATCH_* | SALLOC_* | SRUN_* | JOB_COMPLETION_INDEX | FACIAL_SHARD_COUNT) unset "$name" ;;
  esac
done < <(compgen -e)

tmp="$(mktemp -d "${TMPDIR:-/tmp}/facial-slurm.XXXXXX")"
chmod 700 "$tmp"
conf="$tmp/slurm.conf"
node=facialtest
# Only the commands given it see this cluster (never this shell, so the
# sweep below, which finds our processes by it, never finds this script).
slurm() { SLURM_CONF="$conf" "$@"; }

# The processes of this cluster: the daemons, slurmstepd and the jobs all
# carry SLURM_CONF=$conf in their environment.
cluster_processes() {
  grep -lzsxF "SLURM_CONF=$conf" /proc/[0-9]*/environ 2>/dev/null | cut -d/ -f3 || true
}

wait_until() {  # SECONDS COMMAND...: true once COMMAND succeeds within SECONDS
  local deadline=$((SECONDS + $1))
  shift
  until "$@"; do
    [ "$SECONDS" -lt "$deadline" ] || return 1
    sleep 0.5
  done
}

no_process_left() { [ -z "$(cluster_processes)" ]; }

print_logs() {
  for log in "$tmp"/log/*.log "$tmp"/*.out; do
    [ -f "$log" ] || continue
    echo "---- ${log#"$tmp"/} (last lines)" >&2
    tail -n 15 "$log" >&2
  done
}

stop_everything() {
  local status=$?
  set +e
  if [ -f "$tmp/slurmctld.pid" ]; then
    slurm scancel --quiet --user="$(id -un)" 2>/dev/null
    slurm scontrol shutdown >/dev/null 2>&1
  fi
  wait_until 15 no_process_left
  for pid in $(cluster_processes); do kill -KILL "$pid" 2>/dev/null; done
  if [ -f "$tmp/munge/munged.pid" ]; then kill "$(cat "$tmp/munge/munged.pid")" 2>/dev/null; fi
  [ "$status" -ne 0 ] && [ "$status" -ne 77 ] && print_logs
  rm -rf "$tmp"
  exit "$status"
}
trap stop_everything EXIT
trap 'exit 1' INT TERM

free_ports() {
  python3 -c '
import socket
sockets = [socket.socket() for _ in range(2)]
for s in sockets: s.bind(("127.0.0.1", 0))
print(*[s.getsockname()[1] for s in sockets])'
}

start_munge() {
  mkdir -m 700 "$tmp/munge"
  mungekey --create --keyfile="$tmp/munge/munge.key" >/dev/null 2>&1 || skip "mungekey cannot create a key here"
  munged --force --socket="$tmp/munge/munge.socket" --key-file="$tmp/munge/munge.key" \
    --log-file="$tmp/log/munged.log" --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/munged.seed" \
    || skip "munged cannot start here: $(tail -n 1 "$tmp/log/munged.log" 2>/dev/null)"
}

write_slurm_conf() {
  local ports memory_mb
  read -r -a ports <<< "$(free_ports)"
  memory_mb=$(awk '/MemTotal/ { print int($2 / 2048) }' /proc/meminfo)
  mkdir -p "$tmp/state" "$tmp/spool"
  cat > "$conf" <<EOF
ClusterName=facialtest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=${ports[0]}
SlurmdPort=${ports[1]}
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$tmp/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=$node NodeHostname=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=$memory_mb State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
}

node_idle() { [ "$(slurm sinfo --noheader --nodes="$node" --format=%T 2>/dev/null)" = idle ]; }

start_slurm() {
  write_slurm_conf
  slurm slurmctld -f "$conf" -i 2>"$tmp/log/slurmctld.err" \
    || skip "slurmctld cannot start here: $(tail -n 1 "$tmp/log/slurmctld.err")"
  wait_until 20 slurm scontrol ping >/dev/null \
    || skip "slurmctld did not come up: $(grep -m1 -E 'error|fatal' "$tmp/log/slurmctld.log")"
  slurm slurmd -f "$conf" -N "$node" 2>"$tmp/log/slurmd.err" \
    || skip "slurmd cannot start here: $(tail -n 1 "$tmp/log/slurmd.err")"
  wait_until 30 node_idle || fail "the node never became idle: $(slurm sinfo --noheader --Node --long 2>&1)"
}

# The spec: data/datasets/example.json cut down to a few small images.
write_tiny_spec() {
  python3 - "$source_dir/data/datasets/example.json" "$tmp/tiny.json" "$items" <<'EOF'
import json, sys
spec = json.load(open(sys.argv[1]))
spec.update(count=int(sys.argv[3]), size="64x64", quality="fast")
json.dump(spec, open(sys.argv[2], "w"), indent=2)
EOF
}

# The array's first task submits the merge job (named facial-dataset-merge).
merge_job=""
find_merge() {
  merge_job=$(slurm squeue --noheader --states=all --name=facial-dataset-merge --format=%i 2>/dev/null | head -n 1)
  [ -n "$merge_job" ]
}

job_state() { slurm scontrol show job "$1" 2>/dev/null | grep -o -m1 'JobState=[A-Z_]*' | cut -d= -f2; }
job_ended() { case "$(job_state "$1")" in COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY) return 0 ;; esac; return 1; }

run_array() {
  # The script's own #SBATCH sizes are for real nodes: this node has 2 cores.
  array_job=$(slurm sbatch --parsable --array=0-$((shards - 1)) --cpus-per-task=1 --mem=512M \
                --chdir="$tmp" --output="$tmp/task-%a.out" --export=ALL,FACIAL="$facial" \
                "$source_dir/deploy/slurm/dataset-array.sbatch" "$tmp/tiny.json" "$tmp/sharded")
  wait_until "$timeout_s" find_merge || fail "no merge job was submitted by task 0 of job $array_job"
  wait_until "$timeout_s" job_ended "$merge_job" || fail "the merge job $merge_job did not end within ${timeout_s} s"
  [ "$(job_state "$merge_job")" = COMPLETED ] || fail "the merge job $merge_job ended $(job_state "$merge_job")"
}

check_result() {
  local dir="$tmp/sharded"
  for ((i = 0; i < shards; i++)); do
    [ -s "$dir/shards/labels-$i-of-$shards.jsonl" ] || fail "task $i wrote no $dir/shards/labels-$i-of-$shards.jsonl"
  done
  python3 - "$dir" "$items" <<'EOF'
import json, os, sys
folder, expected = sys.argv[1], int(sys.argv[2])
lines = open(os.path.join(folder, "labels.jsonl")).read().splitlines()
if len(lines) != expected:
    sys.exit(f"FAIL: labels.jsonl has {len(lines)} lines, the spec has {expected} items")
index = json.load(open(os.path.join(folder, "index.json")))
if not index["complete"] or len(index["shards"]) != 4:
    sys.exit(f"FAIL: index.json: complete {index['complete']}, shards {index['shards']} (4 expected)")
for line in lines:
    image = json.loads(line)["image"]
    if not os.path.isfile(os.path.join(folder, image)):
        sys.exit(f"FAIL: labels.jsonl names {image}, which is not in {folder}")
EOF
  "$facial" dataset --spec "$tmp/tiny.json" --out "$tmp/single" --shard 0/1 >"$tmp/single.out" 2>&1 \
    || fail "the unsharded run failed: $(tail -n 3 "$tmp/single.out")"
  # Everything but the shard lists and the index (which names the shards seen).
  diff -r --exclude=shards --exclude=index.json "$tmp/single" "$dir" >&2 \
    || fail "the merged dataset differs from the unsharded run's"
}

mkdir -p "$tmp/log"
start_munge
start_slurm
write_tiny_spec
started=$SECONDS
run_array
echo "the $shards-task array and its merge ran in $((SECONDS - started)) s"
check_result
echo "PASS: $shards shards merged on Slurm equal the unsharded run file for file"
