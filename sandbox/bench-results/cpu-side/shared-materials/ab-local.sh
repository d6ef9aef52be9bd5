#!/usr/bin/env bash
# The CPU side (bench --only cpu-side) of two release builds, alternated twice on this
# repository's CI-like machine (2 cores, lavapipe: the Render stage waits on a software GPU and
# means nothing here; Extract and Prepare are the figures). B: a folder holding the builds B/old
# and B/new; OUT: where the logs go.
B=${B:?a folder holding the release builds old and new}
OUT=${OUT:-.}
export WGPU_BACKEND=vulkan VK_DRIVER_FILES=/usr/share/vulkan/icd.d/lvp_icd.x86_64.json NODEVICE_SELECT=1
COB="--height assets/bench_cobblestone/cobblestone_height.png --normal assets/bench_cobblestone/cobblestone_normal.png --albedo assets/bench_cobblestone/cobblestone_albedo.png --tiling 4"
for round in 1 2; do
  for build in old new; do
    $B/$build bench $COB --only cpu-side --path deferred --path forward --out /tmp/cpu-$build-$round \
      > "$OUT/$build-$round.log" 2>&1
    echo "$build round $round rc $?"
  done
done
