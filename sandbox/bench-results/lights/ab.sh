#!/usr/bin/env bash
# The many-lights bench of two builds in turns, from the repository root:
# ROUNDS=3 OUT=ab-out bash ab.sh OLD_SANDBOX NEW_SANDBOX (each a release build of sandbox).
set -u
export WGPU_BACKEND=vulkan
if ! ls /usr/share/vulkan/icd.d/*nvidia* >/dev/null 2>&1 && [ -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
declare -A BIN=([old]=${1:?old sandbox binary} [new]=${2:?new sandbox binary})
OUT=${OUT:-ab-out}; mkdir -p $OUT
ROUNDS=${ROUNDS:-3}
for round in $(seq 1 $ROUNDS); do
  for v in old new; do
    timeout 140 "${BIN[$v]}" bench --path deferred --path forward --view-angle 45 --size 3840x2160 \
      --frames 200 --only lights --out $OUT/$v-$round > $OUT/$v-$round.log 2>&1
    echo "$v $round rc $? $(date +%T)"
  done
done
