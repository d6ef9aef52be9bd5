#!/usr/bin/env bash
# Device call: the resolve's footprint and maps, by WGSL edits at composition (prof: 59d5ac4 with its neighbour rays unprojected as in c6ebfb5, + wgsl-hook-env.diff).
# The Vulkan loader as in sandbox/BENCHMARKS.md, "How to run"; B: a folder holding the release
# builds this call names (B/old, B/new, ...), built from the commits the header names.
B=${B:?a folder holding the release builds}
mkdir -p /tmp/r/y
export WGPU_BACKEND=vulkan VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
nvidia-smi --query-gpu=name,driver_version --format=csv > /tmp/r/gpu.txt
COB="--height assets/bench_cobblestone/cobblestone_height.png --normal assets/bench_cobblestone/cobblestone_normal.png --albedo assets/bench_cobblestone/cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
K4="--size 3840x2160 --view-angle 45"
run() { local name=$1; for m in normal pom; do timeout 60 env POM_PROFILE_WGSL="$EDIT" $B/prof bench $COB $K4 --method $m --only phases --path deferred --out /tmp/scratch/$name-$m > /tmp/r/y/$name-$m.log 2>&1; echo "$name $m rc $? $(grep 'deferred resolve' /tmp/r/y/$name-$m.log | awk '{print $9}')" | tee -a /tmp/r/y/summary.txt; done; }
EDIT=""; run base
EDIT="xpoint.uv, point.ddx_uv, point.ddy_uv)=>point.uv, vec2<f32>(0.0002, 0.0), vec2<f32>(0.0, 0.0002))"; true
EDIT="let across = interpolate_vertex(t, ray_barycentrics(pixel_ray(centre + vec2<f32>(step.x, 0.0)), p0, p1, p2));=>var across = resolved.vertex; across.uv += vec2<f32>(0.00104, 0.0); ;;let down = interpolate_vertex(t, ray_barycentrics(pixel_ray(centre + vec2<f32>(0.0, step.y)), p0, p1, p2));=>var down = resolved.vertex; down.uv += vec2<f32>(0.0, 0.00147);"; run no-footprint-rays
EDIT="if light_clusters[3] == 0u {=>if true { ;;let across = interpolate_vertex(t, ray_barycentrics(pixel_ray(centre + vec2<f32>(step.x, 0.0)), p0, p1, p2));=>var across = resolved.vertex; across.uv += vec2<f32>(0.00104, 0.0); ;;let down = interpolate_vertex(t, ray_barycentrics(pixel_ray(centre + vec2<f32>(0.0, step.y)), p0, p1, p2));=>var down = resolved.vertex; down.uv += vec2<f32>(0.0, 0.00147);"; run no-rays-no-clusters
EDIT=""; run base-again
tar czf $OUT/r12.tgz -C /tmp r
