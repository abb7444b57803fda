#!/usr/bin/env bash
# The farm on a real Slurm (docs/farm.md, "Tested on a real Slurm"). Usage:
#   pipeline/farm-test.sh [BUILD_DIR]          (default build; run as root, or with slurm-wlm
#                                               and munge installed and a writable /tmp)
# Installs slurm-wlm and munge if missing, writes a one-node cluster (this machine, its CPUs,
# loopback addresses, ports chosen free) into a temporary folder, starts munged, slurmctld and
# slurmd there, and checks:
#  1. a 3-frame moving cache in 2x2 tiles with the photon integrator, submitted by mirage farm
#     and waited for with squeue/scontrol: every frame bit-identical (every channel, idiff with
#     zero tolerance) to a single-machine mirage render of it;
#  2. one render task requeued while it runs (scontrol requeue: SIGTERM, as a lost node's task
#     is rerun) resumes from its partial file, and its frame is still identical;
#  3. mirage farm --skip-existing resubmitted: nothing to submit, no file rewritten; then with
#     one tile and its frame removed, only that tile renders again (the other tasks skip).
# Every daemon it started is stopped by its recorded process id and the folder removed, on
# every exit path. Exit 77 (ctest: skipped) when Slurm cannot be installed or started here.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
BUILD=${1:-build}
case $BUILD in /*) MIRAGE=$BUILD/mirage ;; *) MIRAGE=$ROOT/$BUILD/mirage ;; esac
[ -x "$MIRAGE" ] || { echo "farm-test: no $MIRAGE (build first)"; exit 1; }
T0=$(date +%s)

skip() { echo "farm-test: SKIPPED: $*"; exit 77; }
if ! command -v slurmctld >/dev/null || ! command -v munged >/dev/null || ! command -v idiff >/dev/null; then
    [ "$(id -u)" = 0 ] || skip "slurm-wlm/munge/openimageio-tools missing and not root"
    DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends \
        slurm-wlm munge openimageio-tools >/dev/null || skip "cannot install slurm-wlm and munge"
fi

WORK=$(mktemp -d /tmp/mirage-farm-test.XXXXXX)
PIDS=()
cleanup() {
    local rc=$?
    trap - EXIT INT TERM
    for pid in "${PIDS[@]}"; do kill "$pid" 2>/dev/null || true; done
    for pid in "${PIDS[@]}"; do
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -KILL "$pid" 2>/dev/null || true
    done
    if [ $rc -ne 0 ] && [ $rc -ne 77 ]; then
        echo "farm-test: FAILED ($rc); daemon logs:"
        tail -n 20 "$WORK"/*.log 2>/dev/null || true
        tail -n 20 "$WORK"/shot/logs/*.log 2>/dev/null || true
    fi
    rm -rf "$WORK"
    exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM

# --- a one-node cluster in $WORK ------------------------------------------------------------
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
CTLD_PORT=$(free_port); SLURMD_PORT=$(free_port)
CPUS=$(nproc)
mkdir -p "$WORK/munge" "$WORK/state" "$WORK/spool"
chmod 755 "$WORK/munge"
dd if=/dev/urandom of="$WORK/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$WORK/munge/munge.key"
SOCKET=$WORK/munge/munge.socket
cat > "$WORK/slurm.conf" <<CONF
ClusterName=miragefarmtest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=$(id -un)
SlurmdUser=$(id -un)
AuthType=auth/munge
AuthInfo=socket=$SOCKET,cred_expire=10
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/slurmctld.pid
SlurmdPidFile=$WORK/slurmd.pid
SlurmctldLogFile=$WORK/slurmctld.log
SlurmdLogFile=$WORK/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,bf_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
MpiDefault=none
ReturnToService=2
JobRequeue=1
MinJobAge=3600
KillWait=5
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$CPUS State=UNKNOWN
PartitionName=farmtest Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$WORK/slurm.conf

munged --force --foreground --socket="$SOCKET" --key-file="$WORK/munge/munge.key" \
    --pid-file="$WORK/munge/munged.pid" --log-file="$WORK/munged.log" \
    --seed-file="$WORK/munge/munged.seed" &
PIDS+=($!)
slurmctld -D -i -f "$SLURM_CONF" >"$WORK/slurmctld.out" 2>&1 &
PIDS+=($!)
slurmd -D -N localhost -f "$SLURM_CONF" >"$WORK/slurmd.out" 2>&1 &
PIDS+=($!)
for _ in $(seq 100); do
    sinfo -h -o %t 2>/dev/null | grep -q idle && break
    sleep 0.2
done
sinfo -h -o %t 2>/dev/null | grep -q idle || skip "the one-node Slurm did not come up ($(cat "$WORK"/*.out 2>/dev/null | tail -n 3))"
echo "farm-test: slurm up in $(( $(date +%s) - T0 ))s (munged, slurmctld, slurmd: pids ${PIDS[*]})"

# --- the shot: a moving cache, 3 frames ---------------------------------------------------------
SHOT=$WORK/shot
mkdir -p "$WORK/scene" "$WORK/ref"
for f in 1 2 3; do
    "$MIRAGE" make-asset smoke -o "$WORK/scene/smoke.000$f.vdb" --resolution 16 --seed "$f" >/dev/null
done
cat > "$WORK/scene/shot.toml" <<TOML
[film]
resolution = [48, 32]
tile_size = 4
spp = 1024
seed = 11
[render]
integrator = "photon"
photons = 4000
[camera]
position = [0, 1.2, 4.5]
look_at = [0, 0.9, 0]
fov = 40
[[volume]]
file = "smoke.\$F4.vdb"
shader = "smoke"
density_scale = 4
[[light]]
type = "sun"
direction = [0.6, -0.7, -0.4]
irradiance = 1476
TOML
SCENE=$WORK/scene/shot.toml
for f in 1 2 3; do
    "$MIRAGE" render "$SCENE" --frame "$f" -q -o "$WORK/ref/$f.exr" >/dev/null
done
echo "farm-test: single-machine references in $(( $(date +%s) - T0 ))s"

wait_for_jobs() {  # until none of the shot's jobs is pending or running
    for _ in $(seq 1800); do
        [ -z "$(squeue -h -o %i 2>/dev/null)" ] && return 0
        sleep 0.1
    done
    echo "farm-test: jobs still queued after 180 s:"; squeue; return 1
}

# Each task writes its partial file after every 4-pixel tile, so the kill lands mid-region.
export MIRAGE_PARTIAL_INTERVAL=0
"$MIRAGE" farm "$SCENE" --frames 1-3 --tiles 2x2 --cpus 1 -d "$SHOT" > "$WORK/jobs.out"
cat "$WORK/jobs.out"
RENDER_T00=$(awk '$1 == "render.t00.sh" {print $2}' "$WORK/jobs.out")

# --- 2. requeue one render task while it runs -------------------------------------------------
VICTIM=$SHOT/tiles/0002.t00.exr
for _ in $(seq 1200); do [ -e "$VICTIM.partial" ] || [ -e "$VICTIM" ] && break; sleep 0.05; done
[ -e "$VICTIM" ] && { echo "farm-test: task ${RENDER_T00}_2 finished before it could be killed"; exit 1; }
[ -e "$VICTIM.partial" ] || { echo "farm-test: task ${RENDER_T00}_2 never started"; exit 1; }
scontrol requeue "${RENDER_T00}_2"
echo "farm-test: requeued ${RENDER_T00}_2 while it rendered"
wait_for_jobs

# --- 1. every task completed; frames identical to the single-machine renders -----------------
if scontrol show job 2>/dev/null | grep -o 'JobState=[A-Z_]*' | grep -v COMPLETED; then
    echo "farm-test: a task did not complete"; scontrol show job | grep -E 'JobId|JobState|ExitCode'; exit 1
fi
for f in 1 2 3; do
    idiff -q -a -fail 0 -warn 0 "$WORK/ref/$f.exr" "$SHOT/frames/shot.000$f.exr" >/dev/null ||
        { echo "farm-test: frame $f differs from the single-machine render"; exit 1; }
done
grep -q "restart 1" "$SHOT/logs/render.f0002.t00.log" ||
    { echo "farm-test: the requeued task did not run again"; exit 1; }
RESUMED=$(exrheader "$VICTIM" | sed -n 's/.*mirage:resumed_tiles (type string): "\(.*\)"/\1/p')
[ "${RESUMED:-0}" -ge 1 ] || { echo "farm-test: the requeued task did not resume ($VICTIM)"; exit 1; }
echo "farm-test: 3 frames x 4 tiles identical to single-machine renders; requeued task resumed $RESUMED tiles ($(( $(date +%s) - T0 ))s)"

# --- 3. --skip-existing renders nothing twice ---------------------------------------------------
stamp() { find "$SHOT/frames" "$SHOT/tiles" "$SHOT/photons" -type f -printf '%p %T@ %i\n' | sort; }
BEFORE=$(stamp)
"$MIRAGE" farm "$SCENE" --frames 1-3 --tiles 2x2 --cpus 1 -d "$SHOT" --skip-existing > "$WORK/again.out"
grep -q "nothing to submit" "$WORK/again.out" || { echo "farm-test: a complete shot was resubmitted"; exit 1; }
[ "$(stamp)" = "$BEFORE" ] || { echo "farm-test: --skip-existing rewrote a file"; exit 1; }
# One tile and its frame lost: only that tile is rendered again, and the frame assembled.
rm "$SHOT/tiles/0003.t01.exr" "$SHOT/frames/shot.0003.exr"
KEEP=$(stamp | grep -v -e 0003.t01 -e shot.0003)
"$MIRAGE" farm "$SCENE" --frames 1-3 --tiles 2x2 --cpus 1 -d "$SHOT" --skip-existing > "$WORK/again.out"
grep -q "^assemble.sh" "$WORK/again.out" || { echo "farm-test: nothing was submitted for frame 3"; exit 1; }
wait_for_jobs
[ "$(stamp | grep -v -e 0003.t01 -e shot.0003)" = "$KEEP" ] ||
    { echo "farm-test: --skip-existing rendered a complete tile or photon file again"; exit 1; }
idiff -q -a -fail 0 -warn 0 "$WORK/ref/3.exr" "$SHOT/frames/shot.0003.exr" >/dev/null ||
    { echo "farm-test: re-rendered frame 3 differs"; exit 1; }
echo "farm-test: PASSED in $(( $(date +%s) - T0 ))s"
