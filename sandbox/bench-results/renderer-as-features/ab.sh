#!/usr/bin/env bash
# The cobblestone and street-corner benches of two builds in turns, from the repository root:
# ROUNDS=2 OUT=ab-out bash ab.sh OLD_SANDBOX NEW_SANDBOX (each a release build of sandbox).
set -u
export WGPU_BACKEND=vulkan
if ! ls /usr/share/vulkan/icd.d/*nvidia* >/dev/null 2>&1 && [ -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
declare -A BIN=([old]=${1:?old sandbox binary} [new]=${2:?new sandbox binary})
COB=(--height assets/bench_cobblestone/cobblestone_height.png
  --normal assets/bench_cobblestone/cobblestone_normal.png
  --albedo assets/bench_cobblestone/cobblestone_albedo.png
  --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4
  --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45)
OUT=${OUT:-ab-out}; mkdir -p $OUT/r
ROUNDS=${ROUNDS:-1}
for round in $(seq 1 $ROUNDS); do
  for v in old new; do
    timeout 150 "${BIN[$v]}" bench "${COB[@]}" --size 3840x2160 --view-angle 45 --only phases --only antialiasing \
      --path forward --path deferred --out $OUT/r/$v-cob-$round > $OUT/r/$v-cob-$round.log 2>&1
    echo "$v cob $round rc $? $(date +%T)"
    timeout 150 "${BIN[$v]}" bench --path forward --path deferred --view-angle 45 --size 3840x2160 \
      --only scene-shadows --out $OUT/r/$v-street-$round > $OUT/r/$v-street-$round.log 2>&1
    echo "$v street $round rc $? $(date +%T)"
  done
done
