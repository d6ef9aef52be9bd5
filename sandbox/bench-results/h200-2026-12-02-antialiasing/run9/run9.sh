#!/bin/bash
# Session 17's second device run (issue 32): v2 (history taps without finite_colour) against
# v5 = v2 with the tile as one vec4 a pixel (colour and depth: one workgroup load a tap) and
# v6 = v5 with the nearest offset clamped once after the 3x3 loop.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run9.sh $R/
W=/tmp/w; mkdir -p $W
if command -v xz >/dev/null; then xz -dc .devbin/variants.tar.xz | tar xf - -C $W
else python3 -c "import lzma,sys;sys.stdout.buffer.write(lzma.open('.devbin/variants.tar.xz').read())" | tar xf - -C $W; fi
ls -la $W > $R/variants.txt
cp .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date9.txt
nvidia-smi --query-gpu=name,driver_version --format=csv >> $R/date9.txt 2>&1
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 200 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status9.txt; }
for round in 1 2 3; do
for v in v2-nofinite v5-vec4 v6-vec4-offset; do
  run $v-45-r$round ./$v bench $COB --shadows soft --view-angle 45 --size 3840x2160 --only antialiasing --path forward --path deferred
done
done
for v in v2-nofinite v5-vec4 v6-vec4-offset; do
  run $v-75 ./$v bench $COB --shadows soft --view-angle 75 --size 3840x2160 --only antialiasing --path forward --path deferred
done
cd /tmp && tar czf $OUT/results9.tgz r
for f in $R/*.log; do echo "$(basename $f): $(grep -h 'taa taa' $f | awk '{print $14, $8}' | tr '\n' ' ')"; done
cat $R/status9.txt
