#!/usr/bin/env bash
# Device call: 59d5ac4 (new) against 59d5ac4 + quad-exchange.diff (quad), resolve rows; two rounds.
# The Vulkan loader as in sandbox/BENCHMARKS.md, "How to run"; B: a folder holding the release
# builds this call names (B/old, B/new, ...), built from the commits the header names.
B=${B:?a folder holding the release builds}
mkdir -p /tmp/r/y
export WGPU_BACKEND=vulkan VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
nvidia-smi --query-gpu=name,driver_version --format=csv > /tmp/r/gpu.txt
COB="--height assets/bench_cobblestone/cobblestone_height.png --normal assets/bench_cobblestone/cobblestone_normal.png --albedo assets/bench_cobblestone/cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
run() { local name=$1 b=$2; shift 2; timeout 60 $B/$b bench "$@" --out /tmp/scratch/$b-$name > /tmp/r/y/$b-$name.log 2>&1; echo "$b $name $(grep 'deferred resolve' /tmp/r/y/$b-$name.log | awk '{print $9}' | head -1)" | tee -a /tmp/r/summary.txt; }
for b in new quad new quad; do
  run normal-45 $b $COB --size 3840x2160 --view-angle 45 --method normal --only phases --path deferred
  for a in 0 45 75; do run pom-$a $b $COB --size 3840x2160 --view-angle $a --only phases --path deferred; done
done
tar czf $OUT/r14.tgz -C /tmp r
