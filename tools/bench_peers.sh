#!/usr/bin/env bash
# mira against Mitsuba 3 and Cycles, side by side in the same interleaved rounds, on the
# benchmark scenes of ../shared/bench (see its README.md for the protocol):
#
#   tools/bench_peers.sh [cbox|heavy|all]        (default: all)
#
# - cbox:  the Cornell box (../shared/bench/cbox.mi), 256², 64 spp: whole-process wall time
#          and render-only samples/s (run_peers.py).
# - heavy: the heavy-geometry box, 1 M and 4 M triangles, 256², 16 spp: time to first pixel,
#          peak memory per triangle, render time (run_heavy.py; generates the geometry once).
#
# The peers run from the venv that ../shared/bench/setup.sh makes ($BENCH_DIR/bench-venv).
# Where it is missing, the script says so and times mira alone, giving its ratios against
# the peers' reference figures (../shared/bench/README.md, measured on a 2-core VM): only
# ratios measured in one run compare like with like.
#
# Environment: BENCH_DIR (outputs and venv; default ./bench-out-peers), BENCH_SCRIPTS (the
# peer scripts; default ../shared/bench beside the checkout), MIRA (the binary; default:
# built with cargo build --release), THREADS (default: every core), RUNS (3), WARMUP (1),
# HEAVY_TRIS (1000000,4000000), PEERS (mitsuba_scalar,mitsuba_llvm,cycles).
# With the peers, the run is also drawn as $BENCH_DIR/performance.svg (tools/bench_plot.py).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WHAT="${1:-all}"
case "$WHAT" in cbox | heavy | all) ;; *) echo "usage: $0 [cbox|heavy|all]" >&2; exit 2 ;; esac
SCRIPTS="${BENCH_SCRIPTS:-$ROOT/../shared/bench}"
export BENCH_DIR="${BENCH_DIR:-$PWD/bench-out-peers}"
THREADS="${THREADS:-$(nproc)}"
RUNS="${RUNS:-3}"
WARMUP="${WARMUP:-1}"
HEAVY_TRIS="${HEAVY_TRIS:-1000000,4000000}"
PEERS="${PEERS:-mitsuba_scalar,mitsuba_llvm,cycles}"
VENV="$BENCH_DIR/bench-venv"
JSON="$ROOT/tools/bench_mira_json.sh"

if [ ! -d "$SCRIPTS" ]; then
  echo "bench_peers: no peer scripts at $SCRIPTS (set BENCH_SCRIPTS)" >&2
  exit 1
fi
if [ -z "${MIRA:-}" ]; then
  (cd "$ROOT" && cargo build --release -p mira >&2)
  MIRA="$ROOT/target/release/mira"
fi
mkdir -p "$BENCH_DIR"

peers_here=0
if [ -x "$VENV/bin/python" ] && "$VENV/bin/python" -c "import mitsuba" >/dev/null 2>&1; then
  peers_here=1
fi

# mira's command line for the drivers' --extra (placeholders filled in by them).
extra() {
  echo "mira=$JSON $MIRA render $1 -o {out} --resolution {res} {res} --spp {spp} --seed {seed} --threads {threads}"
}

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

# mira alone, RUNS times after WARMUP: median of one JSON field and of the wall time.
mira_alone() { # scene res spp field
  local scene=$1 res=$2 spp=$3 out="$BENCH_DIR/mira_alone.exr" i t0 t1 line
  : > "$BENCH_DIR/alone.txt"
  for ((i = 0; i < WARMUP + RUNS; i++)); do
    t0=$(date +%s.%N)
    line=$("$JSON" "$MIRA" render "$scene" -o "$out" --resolution "$res" "$res" --spp "$spp" --threads "$THREADS" 2>/dev/null | tail -n 1)
    t1=$(date +%s.%N)
    if ((i >= WARMUP)); then
      echo "$line" | awk -v w="$(echo "$t1 - $t0" | bc)" -v t0="$t0" -F'[:,}]' '{
        for (k = 1; k < NF; k += 2) { gsub(/[ "{]/, "", $k); f[$k] = $(k + 1) }
        printf "%s %s %s %s\n", w, f["render_s"], f["t_render_start_epoch"] - t0, f["peak_mib"] }' >> "$BENCH_DIR/alone.txt"
    fi
  done
}

if [ "$peers_here" = 1 ]; then
  echo "bench_peers: peers from $VENV; mira is $MIRA; $THREADS threads, median of $RUNS runs" >&2
  if [ "$WHAT" != heavy ]; then
    THREADS="$THREADS" RUNS="$RUNS" WARMUP="$WARMUP" PEERS="$PEERS" \
      "$SCRIPTS/cbox_peers.sh" --venv "$VENV" 256 64 --extra "$(extra "$SCRIPTS/cbox.mi")"
  fi
  if [ "$WHAT" != cbox ]; then
    "$VENV/bin/python" "$SCRIPTS/run_heavy.py" --tris "$HEAVY_TRIS" --threads "$THREADS" --runs "$RUNS" \
      --warmup "$WARMUP" --peers "$PEERS" --extra "$(extra "{mi}")"
  fi
  # The run as a chart (tools/bench_plot.py; the README's is drawn from docs/bench/).
  cbox_json="$BENCH_DIR/bench-out/cbox/timings.json"
  heavy_json="$BENCH_DIR/bench-out/heavy/bench/heavy_timings.json"
  # The figures are already printed: a chart that cannot be drawn is reported, not fatal.
  if [ -f "$cbox_json" ]; then
    plot_inputs=("$cbox_json")
    if [ -f "$heavy_json" ]; then
      plot_inputs+=("$heavy_json")
    fi
    python3 "$ROOT/tools/bench_plot.py" "${plot_inputs[@]}" -o "$BENCH_DIR/performance.svg" >&2 ||
      echo "bench_peers: the chart was not drawn (tools/bench_plot.py failed; the figures above stand)" >&2
  fi
  exit 0
fi

echo "bench_peers: Mitsuba 3 and Cycles are not installed here (no venv with mitsuba at $VENV;" >&2
echo "  $SCRIPTS/setup.sh $VENV installs them): timing mira alone and comparing with the" >&2
echo "  peers' reference figures from $SCRIPTS/README.md (another machine: ratios are indicative)" >&2
if [ "$WHAT" != heavy ]; then
  mira_alone "$SCRIPTS/cbox.mi" 256 64
  wall=$(awk '{ print $1 }' "$BENCH_DIR/alone.txt" | median)
  render=$(awk '{ print $2 }' "$BENCH_DIR/alone.txt" | median)
  echo "Cornell box 256², 64 spp, $THREADS threads (median of $RUNS): mira whole process $wall s, render $render s"
  awk -v wall="$wall" -v render="$render" 'BEGIN {
    sps = 256 * 256 * 64 / render
    printf "| renderer | reference wall s | mira wall / it | reference samples/s | mira samples/s / it |\n|---|---|---|---|---|\n"
    printf "| Mitsuba llvm_ad_rgb | 1.63 | %.2f | 3.81 M | %.2f |\n", wall / 1.63, sps / 3.81e6
    printf "| Mitsuba scalar_rgb | 3.82 | %.2f | 1.21 M | %.2f |\n", wall / 3.82, sps / 1.21e6
    printf "| Cycles | 7.14 | %.2f | 0.67 M | %.2f |\n", wall / 7.14, sps / 0.67e6 }'
fi
if [ "$WHAT" != cbox ]; then
  geom="$BENCH_DIR/bench-out/heavy"
  for n in 20 4000000; do
    label=$([ "$n" = 4000000 ] && echo 4M || echo "$n")
    if [ ! -f "$geom/heavy_$label.mi" ]; then
      python3 "$SCRIPTS/heavy_scene.py" --tris "$n" --label "$label" --out "$geom" >/dev/null ||
        { echo "bench_peers: cannot generate the heavy scene (it needs numpy)" >&2; exit 1; }
    fi
  done
  mira_alone "$geom/heavy_20.mi" 256 16
  base=$(awk '{ print $4 }' "$BENCH_DIR/alone.txt" | median)
  mira_alone "$geom/heavy_4M.mi" 256 16
  ttfp=$(awk '{ print $3 }' "$BENCH_DIR/alone.txt" | median)
  render=$(awk '{ print $2 }' "$BENCH_DIR/alone.txt" | median)
  peak=$(awk '{ print $4 }' "$BENCH_DIR/alone.txt" | median)
  awk -v ttfp="$ttfp" -v render="$render" -v peak="$peak" -v base="$base" 'BEGIN {
    bpt = (peak - base) * 1048576 / (3996180 - 20)
    printf "Heavy scene 4M, 256², 16 spp: mira time to first pixel %.2f s, render %.2f s, %.0f bytes per triangle (mira --stats peak memory)\n", ttfp, render, bpt
    printf "| renderer | reference first pixel s | mira / it | reference B/triangle | mira / it | reference render s | mira / it |\n|---|---|---|---|---|---|---|\n"
    printf "| Mitsuba scalar_rgb | 2.58 | %.2f | 118 | %.2f | 1.62 | %.2f |\n", ttfp / 2.58, bpt / 118, render / 1.62
    printf "| Mitsuba llvm_ad_rgb | 2.84 | %.2f | 118 | %.2f | 0.95 | %.2f |\n", ttfp / 2.84, bpt / 118, render / 0.95
    printf "| Cycles | 4.27 | %.2f | 230 | %.2f | 2.38 | %.2f |\n", ttfp / 4.27, bpt / 230, render / 2.38 }'
fi
