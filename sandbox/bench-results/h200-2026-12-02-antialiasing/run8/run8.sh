#!/bin/bash
# Session 17's device run (issue 32): TAA pass variants at 4K (v0 = the tree at 29ebb47;
# v1 packed half-float tile + history taps without finite_colour; v2 taps only; v3 = v2 +
# unjittered position from the jitter, one matrix less; v4 = v3 + packed tile; d1..d3 are
# diagnostics: no history reads, no tonemap in the tile, no 3x3 neighbourhood).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run8.sh $R/
W=/tmp/w; mkdir -p $W
if command -v xz >/dev/null; then xz -dc .devbin/variants.tar.xz | tar xf - -C $W
else python3 -c "import lzma,sys;sys.stdout.buffer.write(lzma.open('.devbin/variants.tar.xz').read())" | tar xf - -C $W; fi
ls -la $W > $R/variants.txt
cp .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date8.txt
nvidia-smi --query-gpu=name,driver_version --format=csv >> $R/date8.txt 2>&1
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 200 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status8.txt; }
for round in 1 2; do
for v in v0-head v1-packed v2-nofinite v3-jitter v4-jitter-packed d1 d2 d3; do
  run $v-45-r$round ./$v bench $COB --shadows soft --view-angle 45 --size 3840x2160 --only antialiasing --path forward --path deferred
done
done
for v in v0-head v3-jitter v4-jitter-packed; do
  run $v-75 ./$v bench $COB --shadows soft --view-angle 75 --size 3840x2160 --only antialiasing --path forward --path deferred
done
cd /tmp && tar czf $OUT/results8.tgz r
for f in $R/*.log; do echo "$(basename $f): $(grep -h 'taa taa' $f | awk '{print $14, $8}' | tr '\n' ' ')"; done
cat $R/status8.txt
