#!/usr/bin/env bash
# Device call: the light-cluster code's cost, by WGSL edits at composition (99cf3fc + wgsl-hook-env.diff).
. "$(dirname "$0")/../setup.sh"
run() { wgsl_variant "$@"; }
VP=$'let view_projection = mat4x4<f32>(cluster_vector(8u), cluster_vector(12u), cluster_vector(16u),\n        cluster_vector(20u));=>let view_projection = frame.view_projection;'
FIRST="let lights = lights_near(in.world_position);=>;;let maps = surface_maps(in, point);=>let lights = lights_near(in.world_position); let maps = surface_maps(in, point);"
EDIT=""; run base
EDIT="if light_clusters[3] == 0u {=>if true {"; run dead
EDIT="$FIRST"; run lights-first
EDIT="$VP"; run uniform-vp
EDIT="$FIRST;;$VP"; run both
EDIT=""; run base-again
tar czf $OUT/r15.tgz -C /tmp r
