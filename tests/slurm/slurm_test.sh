#!/usr/bin/env bash
# End-to-end farm test on a real single-node Slurm cluster started on loopback: its own munge
# key, slurm.conf, ports and state in a temporary folder. Submits the sample in 4 chunks with
# `inkline farm --submit`, waits, and compares every file with a sequential run byte for byte
# (polylines JSON apart from its timings). Stops only the daemons it started, by process id.
#   bash tests/slurm/slurm_test.sh BUILD_DIR
# Skips (exit 0, with a message) when not root or when slurm-wlm and munge cannot be installed.
set -uo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
inkline="$(pwd)/$build/cli/inkline"

skip() { echo "slurm_test: SKIP: $*"; exit 0; }
[ "$(id -u)" -eq 0 ] || skip "needs root to start slurmctld, slurmd and munged"
[ -x "$inkline" ] || { echo "slurm_test: $inkline not built" >&2; exit 1; }
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null; then
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq slurm-wlm munge >/dev/null 2>&1 ||
    skip "slurm-wlm and munge cannot be installed here"
fi
command -v pdfunite >/dev/null || skip "pdfunite (poppler-utils) missing"

tmp=$(mktemp -d /tmp/inkline-slurm.XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null; done
  rm -rf "$tmp"
}
trap cleanup EXIT

# munge: a fresh key, a private socket.
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool" "$tmp/log"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 700 "$tmp/munge"; chmod 400 "$tmp/munge/munge.key"
munged --foreground --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/munge.sock" \
  --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/log/munged.log" --seed-file="$tmp/munge/seed" \
  >"$tmp/log/munged.out" 2>&1 &
pids+=($!)

# Ports away from Slurm's defaults, so a real cluster on this machine is left alone.
node=$(hostname -s)
cpus=$(nproc)
cat >"$tmp/slurm.conf" <<CONF
ClusterName=inkline-test
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$tmp/munge/munge.sock
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool/%n
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
ReturnToService=2
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"
sleep 1
slurmctld -D -f "$SLURM_CONF" >"$tmp/log/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >"$tmp/log/slurmd.out" 2>&1 &
pids+=($!)

fail() {
  echo "slurm_test: FAIL: $*" >&2
  tail -n 20 "$tmp"/log/*.log "$tmp"/log/*.out "$tmp"/out/slurm/logs/*.log 2>/dev/null >&2
  exit 1
}
for _ in $(seq 60); do
  sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)' && break
  sleep 1
done
sinfo -h -o %T 2>/dev/null | grep -qE '^(idle|mixed|allocated)' || fail "the node did not come up"

# The sample in 4 chunks through the farm, then sequentially, and compare.
scene=samples/torus/scene.json
args=(--frames 1:12 --size 512x512 --png "$tmp/out/png/f_%04d.png" --pdf "$tmp/out/pdf/f_%04d.pdf")
start=$(date +%s.%N)
"$inkline" farm "$scene" --chunks 4 -o "$tmp/out" --submit -- "${args[@]}" >"$tmp/log/farm.out" 2>&1 ||
  fail "inkline farm --submit: $(cat "$tmp/log/farm.out")"
for _ in $(seq 300); do
  [ -z "$(squeue -h 2>/dev/null)" ] && break
  sleep 1
done
[ -z "$(squeue -h)" ] || fail "jobs still queued after 300 s"
farm_s=$(echo "$(date +%s.%N) - $start" | bc)
grep -q '^complete' "$tmp/out/slurm/summary.txt" 2>/dev/null || fail "summary: $(cat "$tmp/out/slurm/summary.txt" 2>/dev/null)"
pdfinfo "$tmp/out/sequence.pdf" | grep -q 'Pages: *12' || fail "sequence.pdf does not have 12 pages"

seq_args=(--frames 1:12 --size 512x512 --png "$tmp/seq/png/f_%04d.png" --pdf "$tmp/seq/pdf/f_%04d.pdf")
start=$(date +%s.%N)
"$inkline" render "$scene" -q -o "$tmp/seq" "${seq_args[@]}" || fail "sequential render"
seq_s=$(echo "$(date +%s.%N) - $start" | bc)

differ=0
while IFS= read -r f; do
  if [[ "$f" == *.json ]]; then
    python3 - "$tmp/seq/$f" "$tmp/out/$f" <<'PY' || { echo "differs: $f"; differ=1; }
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
for d in (a, b): d["stats"].pop("ms")
sys.exit(a != b)
PY
  else
    cmp -s "$tmp/seq/$f" "$tmp/out/$f" || { echo "differs: $f"; differ=1; }
  fi
done < <(cd "$tmp/seq" && find . -type f | sort)
[ "$differ" -eq 0 ] || fail "chunked output differs from the sequential run"
echo "slurm_test: PASS: 4 chunks on Slurm match the sequential run byte for byte" \
     "(farm wall ${farm_s}s incl. scheduling, sequential ${seq_s}s)"
