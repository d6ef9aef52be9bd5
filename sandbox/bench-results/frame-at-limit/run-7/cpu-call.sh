#!/usr/bin/env bash
# Device call (run 2026-12-06 on an H100 host; logs in cpu/): the CPU side, old (8da098a) against
# new (90d789a), three alternating rounds, both paths; the new build also times the
# shared-material cases. Tarred into $OUT/cpu.tgz.
# The Vulkan loader as in sandbox/BENCHMARKS.md, "How to run"; B: a folder holding the release
# builds B/old and B/new, built from the commits above.
B=${B:?a folder holding the release builds}
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/cpu
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > /tmp/cpu/gpu.txt 2>&1
( sleep ${STOP:-560}; tar czf $OUT/cpu.tgz -C /tmp cpu ) &
COB="--height assets/bench_cobblestone/cobblestone_height.png --normal assets/bench_cobblestone/cobblestone_normal.png --albedo assets/bench_cobblestone/cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for round in 1 2 3; do
  for build in old new; do
    timeout 150 $B/$build bench $COB --view-angle 45 --only cpu-side --path deferred --path forward \
      --out /tmp/cpu/$build-$round > /tmp/cpu/$build-$round.log 2>&1
    echo "$build round $round rc $?" >> /tmp/cpu/summary.txt
  done
done
tar czf $OUT/cpu.tgz -C /tmp cpu; kill %1 2>/dev/null; cat /tmp/cpu/summary.txt
