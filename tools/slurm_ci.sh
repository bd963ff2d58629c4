#!/usr/bin/env bash
# A real one-node Slurm cluster for CI: installs Debian's slurmctld, slurmd, slurm-client and
# munge (when missing), writes a slurm.conf for this host (CPUs = nproc, proctrack/linuxproc,
# state and spool directories in a temporary folder), starts munged, slurmctld and slurmd in
# the background (no systemd needed), renders a small scene with `mira farm slurm --parts 4
# --submit --wait`, and compares the merged image bit for bit with a one-process render;
# then a classic scene with pre-passes (a pre-pass job before the parts), then a task made
# to fail once (requeued).
# The daemons it started are stopped by their pids when it exits.
#
# usage: tools/slurm_ci.sh [MIRA]    (MIRA: the mira binary, default target/release/mira)
set -euo pipefail
cd "$(dirname "$0")/.."
mira=$(realpath "${1:-target/release/mira}")
[ -x "$mira" ] || { echo "slurm_ci: no mira binary at $mira (cargo build --release)" >&2; exit 1; }

if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null || ! command -v sbatch >/dev/null \
    || ! command -v munged >/dev/null; then
    SUDO=""
    if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends \
        slurmctld slurmd slurm-client munge >/dev/null
fi

# The farm folder must be visible to the tasks at the same path: on one node any folder is.
tmp=$(mktemp -d /tmp/mira-slurm.XXXXXX)
pids=()
cleanup() {
    status=$?
    for pid in "${pids[@]}"; do
        kill "$pid" 2>/dev/null || true
    done
    for pid in "${pids[@]}"; do
        wait "$pid" 2>/dev/null || true
    done
    if [ "$status" != 0 ]; then
        echo "slurm_ci: failed; logs:" >&2
        tail -n 20 "$tmp"/*.log "$tmp"/farm/logs/*.log 2>/dev/null >&2 || true
    fi
    rm -rf "$tmp"
    exit "$status"
}
trap cleanup EXIT

host=$(hostname -s)
mkdir -p "$tmp/munge" "$tmp/state" "$tmp/spool"
chmod 700 "$tmp/munge"
head -c 1024 /dev/urandom > "$tmp/munge/munge.key"
chmod 400 "$tmp/munge/munge.key"
munged --foreground --force --key-file="$tmp/munge/munge.key" --socket="$tmp/munge/munge.socket" \
    --pid-file="$tmp/munge/munged.pid" --log-file="$tmp/munged.log" --seed-file="$tmp/munge/seed" \
    >"$tmp/munged.out.log" 2>&1 &
pids+=($!)

export SLURM_CONF="$tmp/slurm.conf"
cat > "$SLURM_CONF" <<EOF
ClusterName=miraci
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=16817
SlurmdPort=16818
AuthType=auth/munge
AuthInfo=socket=$tmp/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
JobRequeue=1
MpiDefault=none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=ci Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF

slurmctld -D -i -f "$SLURM_CONF" >"$tmp/slurmctld.out.log" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N "$host" >"$tmp/slurmd.out.log" 2>&1 &
pids+=($!)

# Wait (up to 60 s) for the node to be idle.
for _ in $(seq 60); do
    if [ "$(sinfo -h -o %T 2>/dev/null | head -n1)" = "idle" ]; then break; fi
    sleep 1
done
sinfo

scene=scenes/iray_cornell_box.mi
opts=(--resolution 64 48 --spp 8)
"$mira" render "$scene" "${opts[@]}" -o "$tmp/one.exr"
start=$(date +%s.%N)
"$mira" farm slurm "$scene" -o "$tmp/farm.exr" --parts 4 "${opts[@]}" --dir "$tmp/farm" --submit --wait
end=$(date +%s.%N)
echo "slurm_ci: 4 parts and the merge ran in $(awk "BEGIN { print $end - $start }") s"
ls "$tmp/farm/logs"
cmp "$tmp/one.exr" "$tmp/farm.exr"
echo "slurm_ci: the merged image is bit-identical to the one-process render"

# A classic scene with pre-passes (caustics, photon global illumination and final
# gathering): the farm adds a pre-pass job that the parts wait for and read.
sed -e 's/^    finalgather off$/    finalgather on\n    finalgather accuracy 48/' \
    -e 's/caustic photons 200000/caustic photons 20000/' -e 's/globillum photons 100000/globillum photons 10000/' \
    scenes/photons.mi > "$tmp/photons_fg.mi"
grep -q "finalgather on" "$tmp/photons_fg.mi"
copts=(--resolution 60 40)
"$mira" render "$tmp/photons_fg.mi" "${copts[@]}" -o "$tmp/classic_one.exr"
start=$(date +%s.%N)
"$mira" farm slurm "$tmp/photons_fg.mi" -o "$tmp/classic.exr" --parts 4 "${copts[@]}" --dir "$tmp/classic" \
    --submit --wait
end=$(date +%s.%N)
echo "slurm_ci: the pre-pass, 4 parts and the merge ran in $(awk "BEGIN { print $end - $start }") s"
ls "$tmp/classic/logs" | grep -q '^prepass-'
grep -q -- '--prepass' "$tmp/classic/render.sbatch"
cmp "$tmp/classic_one.exr" "$tmp/classic.exr"
echo "slurm_ci: the classic parts read the pre-pass file; the merge is bit-identical to the one-process render"

# A task that fails is requeued once: the same scripts, with task 1's first attempt made to
# fail, still give the same image.
rm -f "$tmp/farm.exr" "$tmp"/farm/part-*.exr
sed -i 's|^status=\$?$|status=$?; if [ "$task" = 1 ] \&\& [ "${SLURM_RESTART_COUNT:-0}" = 0 ]; then status=1; fi|' \
    "$tmp/farm/render.sbatch"
grep -q 'SLURM_RESTART_COUNT:-0}" = 0' "$tmp/farm/render.sbatch"
id=$(sbatch --parsable "$tmp/farm/render.sbatch")
sbatch --parsable --wait --dependency=afterok:"$id" --kill-on-invalid-dep=yes "$tmp/farm/merge.sbatch"
grep -q "requeueing it once" "$tmp/farm/logs/render-${id}_1.log"
cmp "$tmp/one.exr" "$tmp/farm.exr"
echo "slurm_ci: a failed task was requeued once and the merge is still bit-identical"
