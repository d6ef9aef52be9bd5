#!/usr/bin/env bash
# Device call: where the resolve's time goes, by WGSL edits at composition (59d5ac4 with its neighbour rays unprojected as in c6ebfb5, + wgsl-hook-env.diff).
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
EDIT="let shadowed_from = brightest_lights_floor(lights, in.world_position, params.shadowed_lights);=>let shadowed_from = brightest_lights_floor(lights, in.world_position, params.shadowed_lights); if shadowed_from > -1.0 { return vec4<f32>(color, base.a); }"; run no-lights
EDIT="let receives_shadows = receives_scene_shadows(in.object_index);=>let receives_shadows = false;"; run no-scene-shadow
EDIT="let lights = lights_near(in.world_position);=>let lights = LightList(0u, min(frame.light_counts.x, MAX_DIRECTIONAL_LIGHTS), min(frame.light_counts.x, MAX_DIRECTIONAL_LIGHTS));"; run no-clusters
EDIT="textureStore(scene_output, item.pixel, shade(pixel.vertex, point));=>textureStore(scene_output, item.pixel, vec4<f32>(point.uv, point.height, 1.0));"; run no-shade
EDIT="let maps = surface_maps(in, point);=>let maps = SurfaceMaps(vec4<f32>(0.5), point.surface_frame.normal);"; run no-maps
EDIT="var color = ambient_lighting(surface, normal, point.to_eye, environment_occlusion(in, point, surface, normal));=>var color = vec3<f32>(0.0);"; run no-ambient
EDIT="let surface_position = displaced_position(in, point);=>let surface_position = in.world_position;"; run no-displaced-position
EDIT=""; run base-again
tar czf $OUT/r10.tgz -C /tmp r; cat /tmp/r/y/summary.txt
