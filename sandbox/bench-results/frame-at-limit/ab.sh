#!/usr/bin/env bash
# The issue-50 table in one call: every case on each build in turn, from the repository root:
# OUT=ab-out bash ab.sh OLD_SANDBOX NEW_SANDBOX [BEFORE_LAYERS_SANDBOX] (release builds of sandbox).
# Cases run most needed first, each under its own timeout, so a call cut short keeps what ran.
set -u
export WGPU_BACKEND=vulkan
if ! ls /usr/share/vulkan/icd.d/*nvidia* >/dev/null 2>&1 && [ -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
OLD=${1:?old sandbox binary}; NEW=${2:?new sandbox binary}; BEFORE_LAYERS=${3:-}
OUT=${OUT:-ab-out}; mkdir -p "$OUT"
COB="--height assets/bench_cobblestone/cobblestone_height.png
  --normal assets/bench_cobblestone/cobblestone_normal.png
  --albedo assets/bench_cobblestone/cobblestone_albedo.png
  --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4
  --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
K4="--size 3840x2160 --view-angle 45"
# name, builds (old+new or new), arguments
bench() {
  local name=$1 builds=$2; shift 2
  for build in $builds; do
    local bin=$NEW; [ "$build" = old ] && bin=$OLD; [ "$build" = before-layers ] && bin=$BEFORE_LAYERS
    local start=$(date +%s)
    timeout ${LIMIT:-120} "$bin" bench "$@" --out "$OUT/$build-$name" > "$OUT/$build-$name.log" 2>&1
    echo "$build $name rc $? $(( $(date +%s) - start )) s" | tee -a "$OUT/summary.txt"
  done
}
bench overdraw "old new" --path deferred --path forward --only overdraw
bench depth-offset-45 "old new" $COB $K4 --depth-offset --only phases --path deferred --path forward
bench phases-45 "old new" $COB $K4 --only phases --only seed-port --path deferred
bench scene-shadows "old new" $K4 --only scene-shadows --path deferred
bench depth-offset-taa "old new" $COB $K4 --depth-offset --only antialiasing --path deferred
bench taa "old new" $COB $K4 --only antialiasing --path deferred
bench cpu-side "old new" $COB --view-angle 45 --only cpu-side --path deferred --path forward
bench cpu-side-2 "old new" $COB --view-angle 45 --only cpu-side --path deferred --path forward
bench phases-0 "old new" $COB --size 3840x2160 --view-angle 0 --only phases --only seed-port --path deferred
bench phases-75 "old new" $COB --size 3840x2160 --view-angle 75 --only phases --only seed-port --path deferred
bench normal-45 "old new" $COB $K4 --method normal --only phases --path deferred
bench lights-environment "old new" $COB $K4 --only environment --only lights --path deferred
bench layers-triplanar "new" $COB $K4 --only layers --only triplanar --path deferred --path forward
[ -n "$BEFORE_LAYERS" ] && bench phases-45 "before-layers" $COB $K4 --only phases --path deferred
bench versus-mesh "new" --size 1920x1080 --view-angle 45 --only versus-mesh --path deferred --path forward
