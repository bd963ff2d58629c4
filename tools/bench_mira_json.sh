#!/usr/bin/env bash
# Runs a `mira render …` command line with `--stats` and prints its figures as the one JSON
# line the peer drivers of ../shared/bench read (render_s, t_render_start_epoch), with the
# scene, acceleration and peak-memory figures beside them. mira's own stdout goes to
# stderr, so the JSON line is the last line on stdout.
#
#   tools/bench_mira_json.sh target/release/mira render SCENE.mi -o OUT.exr --spp 64 …
set -euo pipefail
start=$(date +%s.%N)
stats=$("$@" --stats)
echo "$stats" >&2
echo "$stats" | awk -v start="$start" '
  /^scene:/        { scene = $2 }
  /^acceleration:/ { accel = $(NF - 1) }
  /^render:/       { render = $2 }
  /^samples:/      { samples = $2 }
  /^peak memory:/  { peak = $3 }
  END {
    if (render == "") { print "bench_mira_json: no --stats figures from mira" > "/dev/stderr"; exit 1 }
    # Rendering starts once the scene is translated and the acceleration structure built
    # (both timed by mira from its start, a few ms after the spawn).
    printf "{\"render_s\": %s, \"t_render_start_epoch\": %.6f, \"scene_s\": %s, \"accel_s\": %s, \"samples\": %s, \"peak_mib\": %s}\n",
      render, start + scene + accel, scene, accel, samples, (peak == "" ? "null" : peak)
  }'
