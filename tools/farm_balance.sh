#!/usr/bin/env bash
# Equal work per farm part: renders the Cornell box as N parts, one after the other, each
# part R times, and prints each part's wall time and CPU time (user + system), minimum and
# median over the repeats, with the spread (largest over smallest, minus 1) — for the path
# engine (scenes/iray_cornell_box.mi) and the classic engine (the same box with mental ray
# shaders: mib_illum_lambert walls, an area light through mib_light_point, adaptive
# sampling, optionally final gathering read from a `mira prepass` file).
#
# usage: tools/farm_balance.sh [MIRA] [N] [R]   (default target/release/mira 4 5)
# On a shared machine the wall times carry the other processes' load; the minimum over the
# repeats is the least disturbed, and `--threads 1` keeps a part on one core.
set -euo pipefail
cd "$(dirname "$0")/.."
mira=$(realpath "${1:-target/release/mira}")
n=${2:-4}
reps=${3:-5}
tmp=$(mktemp -d /tmp/mira-balance.XXXXXX)
trap 'rm -rf "$tmp"' EXIT

# The classic Cornell box: the MDL materials and light replaced by mental ray shaders.
python3 - scenes/iray_cornell_box.mi "$tmp/classic_cornell.mi" "$tmp/classic_cornell_fg.mi" <<'EOF'
import re, sys
text = open(sys.argv[1]).read()
head = text.index('$include "base.mdl"')
light = text.index('light "Light_lgt"')
end = text.index('end light', light) + len('end light')
classic = '''$include "base.mi"
material "white" "mib_illum_lambert" ("diffuse" 0.7 0.7 0.7, "lights" ["Light_inst"]) end material
material "green" "mib_illum_lambert" ("diffuse" 0.15 0.7 0.15, "lights" ["Light_inst"]) end material
material "red" "mib_illum_lambert" ("diffuse" 0.7 0.15 0.15, "lights" ["Light_inst"]) end material
light "Light_lgt" "mib_light_point" ("color" 0.9 0.85 0.8, "shadow" on)
    origin 0 0 0
    rectangle 130 0 0  0 105 0  4 4
end light'''
out = text[:head] + classic + text[end:]
options = 'options "Options"\n'
assert options in out
out = re.sub(r'attribute integer "progressive_rendering_max_samples" 100\n', '', out)
plain = out.replace(options, options + '    samples 0 2\n    contrast 0.05 0.05 0.05 1\n')
open(sys.argv[2], 'w').write(plain)
fg = plain.replace(options, options + '    finalgather on\n    finalgather accuracy 64\n')
open(sys.argv[3], 'w').write(fg)
EOF

# measure LABEL SCENE [render options…]: every part R times; prints min and median.
measure() {
    local label=$1 scene=$2
    shift 2
    echo "== $label: $n parts, $reps runs each ($*)"
    local walls=() cpus=()
    for k in $(seq "$n"); do
        local w=() c=()
        for _ in $(seq "$reps"); do
            /usr/bin/time -f "%e %U %S" -o "$tmp/t" "$mira" render "$scene" --part "$k/$n" -o "$tmp/p$k.exr" \
                --threads 1 "$@" 2>"$tmp/err" >/dev/null || { cat "$tmp/err"; exit 1; }
            read -r e u s < "$tmp/t"
            w+=("$e")
            c+=("$(awk "BEGIN { print $u + $s }")")
        done
        local wmin wmed cmin cmed
        wmin=$(printf '%s\n' "${w[@]}" | sort -g | head -n1)
        wmed=$(printf '%s\n' "${w[@]}" | sort -g | sed -n "$(( (reps + 1) / 2 ))p")
        cmin=$(printf '%s\n' "${c[@]}" | sort -g | head -n1)
        cmed=$(printf '%s\n' "${c[@]}" | sort -g | sed -n "$(( (reps + 1) / 2 ))p")
        echo "part $k/$n: wall min $wmin median $wmed s; cpu min $cmin median $cmed s"
        walls+=("$wmin")
        cpus+=("$cmin")
    done
    local parts=()
    for k in $(seq "$n"); do parts+=("$tmp/p$k.exr"); done
    "$mira" merge "${parts[@]}" -o "$tmp/merged.exr" 2>/dev/null
    spread() { printf '%s\n' "$@" | sort -g | awk 'NR == 1 { lo = $1 } { hi = $1 } END { printf "%.1f %%", (hi / lo - 1) * 100 }'; }
    echo "spread of the minima: wall $(spread "${walls[@]}"), cpu $(spread "${cpus[@]}")"
}

measure "path engine, Cornell box" scenes/iray_cornell_box.mi --resolution 320 240 --spp 64
measure "classic engine, Cornell box (direct light, adaptive)" "$tmp/classic_cornell.mi" --resolution 320 240
"$mira" prepass "$tmp/classic_cornell_fg.mi" -o "$tmp/fg.prepass" --resolution 320 240 --threads 1 2>&1 | tail -n1
measure "classic engine, Cornell box with final gathering read from a pre-pass file" "$tmp/classic_cornell_fg.mi" \
    --resolution 320 240 --prepass "$tmp/fg.prepass"
