#!/bin/sh
# Renders a scene with mira and Mitsuba 3 (two seeds each) and compares them.
#   tools/compare/run.sh [SCENE.mi]            (default: scenes/iray_cornell_box.mi)
# Environment: OUT (work dir, default /tmp/mira-compare), SPP (1024), RES (256),
# TARGET (cargo target dir, default /tmp/cmp-target), NOTES (where the PNGs go, default $OUT/report).
# Needs: cargo, python3 with mitsuba, numpy, OpenEXR (flip-evaluator, scikit-image, pillow).
set -eu
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
SCENE=$(cd "$(dirname "${1:-$ROOT/scenes/iray_cornell_box.mi}")" && pwd)/$(basename "${1:-iray_cornell_box.mi}")
OUT=${OUT:-/tmp/mira-compare}; SPP=${SPP:-1024}; RES=${RES:-256}
TARGET=${TARGET:-/tmp/cmp-target}; NOTES=${NOTES:-$OUT/report}
mkdir -p "$OUT"

cargo build --release -p mira --manifest-path "$ROOT/Cargo.toml" --target-dir "$TARGET"
cargo build --release --manifest-path "$ROOT/tools/compare/export_obj/Cargo.toml" --target-dir "$TARGET"

# A copy of the scene with a one-pixel box filter (the options block's `filter` line).
grep -q '^[[:space:]]*filter[[:space:]]' "$SCENE" || { echo "no 'filter' line in $SCENE" >&2; exit 1; }
sed 's/^\([[:space:]]*\)filter[[:space:]].*/\1filter box 1 1/' "$SCENE" > "$OUT/scene_box.mi"

"$TARGET/release/export_obj" "$OUT/scene_box.mi" "$OUT/export"
for s in 0 1; do
  "$TARGET/release/mira" render "$OUT/scene_box.mi" -I "$(dirname "$SCENE")" --resolution "$RES" "$RES" \
    --spp "$SPP" --seed $s -o "$OUT/mira_s$s.exr" --stats
done
for s in 1 2; do
  python3 "$ROOT/tools/compare/mitsuba_scene.py" "$OUT/export" "$OUT/mitsuba" --resolution "$RES" "$RES" \
    --spp "$SPP" --seed $s --render "$OUT/mitsuba_s$s.exr"
done
python3 "$ROOT/tools/compare/metrics.py" --mira "$OUT/mira_s0.exr" "$OUT/mira_s1.exr" \
  --ref "$OUT/mitsuba_s1.exr" "$OUT/mitsuba_s2.exr" --outdir "$NOTES" | tee "$NOTES.txt"
