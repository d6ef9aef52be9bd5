#!/usr/bin/env bash
# Device call: where the resolve's time goes, by WGSL edits at composition (59d5ac4 with its neighbour rays unprojected as in c6ebfb5, + wgsl-hook-env.diff).
. "$(dirname "$0")/../setup.sh"
run() { wgsl_variant "$@"; }
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
