#!/usr/bin/env bash
# Renders every scene in scenes/ at a low resolution and prints a digest of each image's
# pixels (EXR: every frame buffer, linear floats; the digest covers every channel's samples
# bit for bit, not the file's bytes: crates/imageio/examples/exr_digest.rs), one
# "DIGEST  SCENE" line per scene, sorted.
#
#   tools/scene_hashes.sh [MIRA]            print the digests (MIRA: the binary to run,
#                                           default target/release/mira)
#   tools/scene_hashes.sh --check [MIRA]    compare with tools/scene_hashes.txt; exit 1
#                                           naming every scene whose image changed
#   tools/scene_hashes.sh --update [MIRA]   rewrite tools/scene_hashes.txt
#
# A refactoring must leave every image bit-identical (CI runs --check). A change that is
# meant to change images updates the file in the same commit and says why.
#
# The renders use the pure-Rust BVH (`--accel rust`): Embree picks its traversal code by
# the processor's vector units, which can move a hit in the last bit from one machine to
# another; mira's own code gives the same bits on any x86-64 machine with the same build.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=print
case "${1:-}" in
--check) mode=check; shift ;;
--update) mode=update; shift ;;
esac
mira="${1:-target/release/mira}"
reference=tools/scene_hashes.txt

out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT

cargo build --quiet --release -p imageio --example exr_digest
digest=target/release/examples/exr_digest

for scene in scenes/*.mi; do
    name="$(basename "$scene" .mi)"
    "$mira" render "$scene" --resolution 40 30 --spp 4 --fg-rays 8 --threads 2 --seed 7 \
        --accel rust -o "$out/$name.exr" >"$out/$name.log" 2>&1 || {
        echo "scene_hashes: $scene failed to render:" >&2
        cat "$out/$name.log" >&2
        exit 1
    }
    echo "$("$digest" "$out/$name.exr" | cut -d' ' -f1)  $scene"
done | sort -k2 >"$out/hashes.txt"

case "$mode" in
print) cat "$out/hashes.txt" ;;
update)
    cp "$out/hashes.txt" "$reference"
    echo "scene_hashes: wrote $reference ($(wc -l <"$reference") scenes)"
    ;;
check)
    if diff -u "$reference" "$out/hashes.txt"; then
        echo "scene_hashes: all $(wc -l <"$reference") scenes render bit-identical to $reference"
    else
        echo "scene_hashes: the images above changed (- expected, + now)" >&2
        exit 1
    fi
    ;;
esac
