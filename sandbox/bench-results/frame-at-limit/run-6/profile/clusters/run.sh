#!/usr/bin/env bash
# Device call: the light-cluster code's cost, by WGSL edits at composition (99cf3fc + wgsl-hook-env.diff).
# The Vulkan loader as in sandbox/BENCHMARKS.md, "How to run"; B: a folder holding the release
# build this call names (B/prof).
B=${B:?a folder holding the release builds}
mkdir -p /tmp/r/y
export WGPU_BACKEND=vulkan VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
nvidia-smi --query-gpu=name,driver_version --format=csv > /tmp/r/gpu.txt
COB="--height assets/bench_cobblestone/cobblestone_height.png --normal assets/bench_cobblestone/cobblestone_normal.png --albedo assets/bench_cobblestone/cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
K4="--size 3840x2160 --view-angle 45"
run() { local name=$1; for m in normal pom; do timeout 60 env POM_PROFILE_WGSL="$EDIT" $B/prof bench $COB $K4 --method $m --only phases --path deferred --out /tmp/scratch/$name-$m > /tmp/r/y/$name-$m.log 2>&1; echo "$name $m rc $? $(grep 'deferred resolve' /tmp/r/y/$name-$m.log | awk '{print $9}')" | tee -a /tmp/r/y/summary.txt; done; }
VP=$'let view_projection = mat4x4<f32>(cluster_vector(8u), cluster_vector(12u), cluster_vector(16u),\n        cluster_vector(20u));=>let view_projection = frame.view_projection;'
FIRST="let lights = lights_near(in.world_position);=>;;let maps = surface_maps(in, point);=>let lights = lights_near(in.world_position); let maps = surface_maps(in, point);"
EDIT=""; run base
EDIT="if light_clusters[3] == 0u {=>if true {"; run dead
EDIT="$FIRST"; run lights-first
EDIT="$VP"; run uniform-vp
EDIT="$FIRST;;$VP"; run both
EDIT=""; run base-again
tar czf $OUT/r15.tgz -C /tmp r
