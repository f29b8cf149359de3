#!/bin/bash
# Runs the user guide's Slurm array job on a single-node Slurm started here, merges its shards
# with a dependent job, and checks the merge is bit-identical to one unsharded run.
#
# Opt-in, as root on Debian 12 (or similar) without systemd: installs slurmd, slurmctld and
# munge from the distribution's packages if sbatch is missing, starts munged, slurmctld and
# slurmd by hand in a temp dir (own munge socket and key, cgroup-free slurm.conf, default
# ports 6817/6818 must be free) and stops them on exit. Writes no tracked file. Run from the
# repository root: `sudo scripts/slurm-test.sh`; needs cargo to build the render example.
# Ends with one line saying what it checked; exits non-zero with the reason on any failure.
set -euo pipefail

SHARDS=4 PASSES=2 SIZE=32x32 PHOTONS=20000 SCENE=cornell-box
WAIT=300 # seconds any one wait (node up, a job) may take

fail() {
    echo "slurm-test: FAILED: $*" >&2
    exit 1
}
[ "$(id -u)" = 0 ] || fail "run as root (it installs packages and starts Slurm's daemons)"
[ -f docs/guide.md ] || fail "run from the repository root (docs/guide.md not found)"

tmp=$(mktemp -d /tmp/slurm-test.XXXXXX)
chmod 755 "$tmp"
pids=()
cleanup() {
    local status=$?
    set +e
    [ -n "${jobs_started:-}" ] && scancel "$jobs_started" 2>/dev/null
    for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null; done
    for pid in "${pids[@]}"; do
        for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
        kill -9 "$pid" 2>/dev/null
    done
    if [ "$status" != 0 ]; then
        for log in "$tmp"/*.log "$tmp"/run/*.log; do
            [ -f "$log" ] && { echo "--- $log (last lines)" >&2; tail -n 15 "$log" >&2; }
        done
    fi
    rm -rf "$tmp"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

if ! command -v sbatch >/dev/null || ! command -v slurmd >/dev/null || ! command -v munged >/dev/null; then
    echo "slurm-test: installing slurmd slurmctld munge (apt-get)" >&2
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq >"$tmp/apt.log" 2>&1 || fail "apt-get update"
    apt-get install -y -qq --no-install-recommends slurmd slurmctld slurm-client munge >"$tmp/apt.log" 2>&1 ||
        fail "apt-get install slurmd slurmctld slurm-client munge"
fi

# munge: its own key and socket, so a system munged (if any) is left alone.
mkdir -p "$tmp/munge"
dd if=/dev/urandom of="$tmp/munge/munge.key" bs=1024 count=1 status=none
chmod 755 "$tmp/munge" && chmod 400 "$tmp/munge/munge.key"
socket="$tmp/munge/munge.socket"
/usr/sbin/munged --force --foreground --key-file="$tmp/munge/munge.key" --socket="$socket" \
    --pid-file="$tmp/munge/munged.pid" --seed-file="$tmp/munge/munged.seed" \
    --log-file="$tmp/munged.log" >>"$tmp/munged.log" 2>&1 &
pids+=($!)
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
munge --socket="$socket" -n </dev/null | unmunge --socket="$socket" >/dev/null ||
    fail "munged does not answer on $socket"

# slurm.conf: one node, this machine as slurmd -C sees it; no cgroups, accounting or systemd.
node=$(slurmd -C | head -n 1)
host=$(echo "$node" | sed -n 's/^NodeName=\([^ ]*\).*/\1/p')
[ -n "$host" ] || fail "slurmd -C gave no NodeName: $node"
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/run/shards"
export SLURM_CONF="$tmp/slurm.conf"
cat >"$SLURM_CONF" <<EOF
ClusterName=pmtest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
ProctrackType=proctrack/pgid
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
DependencyParameters=kill_invalid_depend
MpiDefault=none
ReturnToService=2
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
$node
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -D -i -f "$SLURM_CONF" >>"$tmp/slurmctld.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" >>"$tmp/slurmd.log" 2>&1 &
pids+=($!)
state=
for _ in $(seq $((WAIT * 2))); do
    state=$(sinfo -h -N -n "$host" -o %t 2>/dev/null || true)
    [ "$state" = idle ] && break
    sleep 0.5
done
[ "$state" = idle ] || fail "node $host not idle after ${WAIT} s (sinfo says '${state:-nothing}')"

# The render example, built as the guide says and copied to the folder the jobs run in.
cargo build --quiet --release --example render || fail "cargo build --release --example render"
cp "${CARGO_TARGET_DIR:-target}/release/examples/render" "$tmp/run/render" ||
    fail "no render binary under ${CARGO_TARGET_DIR:-target}/release/examples"

# The guide's array job, scaled down: fewer, shorter shards on a small image, one CPU each.
awk '/^#SBATCH --job-name=pm-shards/ { take = 1; print "#!/bin/bash" } take && /^```/ { exit }
     take { print }' docs/guide.md |
    sed -e "s/--passes-per-shard [0-9]*/--passes-per-shard $PASSES/" \
        -e "s/--photons [0-9]*/--photons $PHOTONS --size $SIZE/" >"$tmp/run/job.sh"
grep -q -- '--shard-index-from slurm' "$tmp/run/job.sh" && grep -q -- "--scene $SCENE" "$tmp/run/job.sh" ||
    fail "the guide's Slurm job (#SBATCH --job-name=pm-shards) not found as expected in docs/guide.md"

cd "$tmp/run"
array=$(sbatch --parsable --array=0-$((SHARDS - 1)) --cpus-per-task=1 --output=shard-%a.log job.sh) ||
    fail "sbatch of the array job"
array=${array%%;*}
jobs_started=$array
# sbatch --wait returns 0 even for a merge cancelled because a shard failed: check the files.
timeout "$WAIT" sbatch --wait --parsable --dependency="afterok:$array" --output=merge.log \
    --job-name=pm-merge --wrap "./render --merge shards/shard-*.exr --out merged.exr" >/dev/null ||
    fail "the merge job (after array job $array) did not succeed"
shards=$(find shards -name '*.exr' | wc -l)
[ "$shards" = "$SHARDS" ] || fail "array job $array wrote $shards of $SHARDS shards"
[ -f merged.exr ] || fail "the merge job wrote no merged.exr: $(tail -n 3 merge.log 2>/dev/null)"

./render --scene "$SCENE" --mode progressive --photons "$PHOTONS" --size "$SIZE" --threads 1 \
    --passes $((SHARDS * PASSES)) --out whole.exr >whole.log 2>&1 || fail "the unsharded run: $(cat whole.log)"
cmp merged.exr whole.exr || fail "the merged image differs from the unsharded run"
echo "slurm-test: $SHARDS array shards of $PASSES passes merged by Slurm equal one $((SHARDS * PASSES))-pass run, bit for bit ($SCENE $SIZE)"
