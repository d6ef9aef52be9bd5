#!/usr/bin/env bash
# Device call: the issue-50 table, old (3a6df78) against new (59d5ac4), then mid (c6ebfb5, the last session's end) on the rows this session changed; tarred into $OUT/ab.tgz.
# The Vulkan loader as in sandbox/BENCHMARKS.md, "How to run"; B: a folder holding the release
# builds this call names (B/old, B/new, ...), built from the commits the header names.
B=${B:?a folder holding the release builds}
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/ab; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > /tmp/ab/gpu.txt 2>&1
( sleep ${STOP:-560}; tar czf $OUT/ab.tgz -C /tmp ab ) &
LIMIT=${LIMIT:-100} OUT=/tmp/ab bash sandbox/bench-results/frame-at-limit/ab.sh $B/old $B/new
COB="--height assets/bench_cobblestone/cobblestone_height.png --normal assets/bench_cobblestone/cobblestone_normal.png --albedo assets/bench_cobblestone/cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
K4="--size 3840x2160 --view-angle 45"
mid() { local name=$1; shift; timeout 60 $B/mid bench "$@" --out /tmp/ab/mid-$name > /tmp/ab/mid-$name.log 2>&1; echo "mid $name rc $?" >> /tmp/ab/summary.txt; }
mid overdraw --path deferred --only overdraw
mid phases-45 $COB $K4 --only phases --only seed-port --path deferred
mid normal-45 $COB $K4 --method normal --only phases --path deferred
mid depth-offset-45 $COB $K4 --depth-offset --only phases --path deferred
mid scene-shadows $K4 --only scene-shadows --path deferred
mid lights-environment $COB $K4 --only environment --only lights --path deferred
tar czf $OUT/ab.tgz -C /tmp ab; kill %1 2>/dev/null; cat /tmp/ab/summary.txt
