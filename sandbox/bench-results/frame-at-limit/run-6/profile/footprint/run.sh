#!/usr/bin/env bash
# Device call: the resolve's footprint and maps, by WGSL edits at composition (prof: 59d5ac4 with its neighbour rays unprojected as in c6ebfb5, + wgsl-hook-env.diff).
. "$(dirname "$0")/../setup.sh"
run() { wgsl_variant "$@"; }
EDIT=""; run base
EDIT="xpoint.uv, point.ddx_uv, point.ddy_uv)=>point.uv, vec2<f32>(0.0002, 0.0), vec2<f32>(0.0, 0.0002))"; true
EDIT="let across = interpolate_vertex(t, ray_barycentrics(pixel_ray(centre + vec2<f32>(step.x, 0.0)), p0, p1, p2));=>var across = resolved.vertex; across.uv += vec2<f32>(0.00104, 0.0); ;;let down = interpolate_vertex(t, ray_barycentrics(pixel_ray(centre + vec2<f32>(0.0, step.y)), p0, p1, p2));=>var down = resolved.vertex; down.uv += vec2<f32>(0.0, 0.00147);"; run no-footprint-rays
EDIT="if light_clusters[3] == 0u {=>if true { ;;let across = interpolate_vertex(t, ray_barycentrics(pixel_ray(centre + vec2<f32>(step.x, 0.0)), p0, p1, p2));=>var across = resolved.vertex; across.uv += vec2<f32>(0.00104, 0.0); ;;let down = interpolate_vertex(t, ray_barycentrics(pixel_ray(centre + vec2<f32>(0.0, step.y)), p0, p1, p2));=>var down = resolved.vertex; down.uv += vec2<f32>(0.0, 0.00147);"; run no-rays-no-clusters
EDIT=""; run base-again
tar czf $OUT/r12.tgz -C /tmp r
