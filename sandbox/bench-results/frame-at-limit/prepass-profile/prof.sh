#!/usr/bin/env bash
# Where the prepass (visibility) phase's time goes on a frame of the polygon pass: a release build
# of sandbox with prepass-stops-env.diff applied leaves out, by environment variable, the keys'
# clear (POM_PROFILE_PREPASS_NO_CLEAR), the polygon pass (POM_PROFILE_NO_POLYGONS) and the depth
# pass after them (POM_PROFILE_PREPASS_NO_DEPTH_PASS: the clear's compute pass ends the phase).
# All three left out times an empty compute pass: what the phase's timestamps cost alone.
# From the repository root: OUT=prof-out bash prof.sh BIN [SIZE].
set -u
BIN=$1; SIZE=${2:-3840x2160}; OUT=${OUT:-prof-out}; mkdir -p "$OUT"
COB="--height assets/bench_cobblestone/cobblestone_height.png
  --normal assets/bench_cobblestone/cobblestone_normal.png
  --albedo assets/bench_cobblestone/cobblestone_albedo.png
  --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4
  --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
run() { local name=$1; shift; local s=$(date +%s)
  env "$@" timeout 120 $BIN bench $COB --size $SIZE --view-angle 45 --only phases --path deferred $EXTRA --out "$OUT/$name" > "$OUT/$name.log" 2>&1
  echo "$name rc $? $(( $(date +%s) - s ))s $(grep -E 'deferred (resolve|prepass)' "$OUT/$name.log" | awk "{print \$NF, \$8}" | tr '\n' ' ')" | tee -a "$OUT/summary.txt"; }
for EXTRA in "" "--depth-offset"; do
  run prepass${EXTRA:+-do} POM_PROFILE_NONE=1
  run no-clear${EXTRA:+-do} POM_PROFILE_PREPASS_NO_CLEAR=1
  run no-polygons${EXTRA:+-do} POM_PROFILE_NO_POLYGONS=1
  run no-depth-pass${EXTRA:+-do} POM_PROFILE_PREPASS_NO_DEPTH_PASS=1
  run clear-only${EXTRA:+-do} POM_PROFILE_NO_POLYGONS=1 POM_PROFILE_PREPASS_NO_DEPTH_PASS=1
  run nothing${EXTRA:+-do} POM_PROFILE_PREPASS_NO_CLEAR=1 POM_PROFILE_NO_POLYGONS=1 POM_PROFILE_PREPASS_NO_DEPTH_PASS=1
done
