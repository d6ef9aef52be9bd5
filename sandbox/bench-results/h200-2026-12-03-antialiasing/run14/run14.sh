#!/bin/bash
# Session 20's second device run (issue 32): the antialiasing group at 4K, both paths, 45° and
# 75°, the cobblestones tiled 1, 4 and 8 times (magnified to minified), three builds in turn:
# v10 = 2f2d1f3 (the post filter without a mip bias, its bilinear read from four loads),
# v11 = 04c9972 (POST_FILTER_MIP_BIAS = -1), v12 = v11 + FXAA's read through a sampler.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan
R=/tmp/r14; mkdir -p $R
cp .devbin/run14.sh $R/
W=/tmp/w; mkdir -p $W
if command -v xz >/dev/null; then xz -dc .devbin/variants14.tar.xz | tar xf - -C $W
else python3 -c "import lzma,sys;sys.stdout.buffer.write(lzma.open('.devbin/variants14.tar.xz').read())" | tar xf - -C $W; fi
cp .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date14.txt
nvidia-smi --query-gpu=name,driver_version --format=csv >> $R/date14.txt 2>&1
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 240 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" >> $R/status14.txt; }
for tiling in 1 4 8; do
for angle in 45 75; do
for v in v10 v11 v12; do
  run $v-aa-$angle-t$tiling ./$v bench $COB --tiling $tiling --shadows soft --view-angle $angle --size 3840x2160 --only antialiasing --path forward --path deferred
done
done
done
cd /tmp && tar czf $OUT/results14.tgz r14
for f in $R/v1*-aa-*.log; do echo "== $(basename $f .log)"; grep -h "^antialiasing" $f | grep "post_filter\|fxaa, 50\|off, 50\|taa taa" | awk '{printf "%s %s ", $8, $13; for(i=14;i<=NF;i++) printf "%s ", $i; print ""}'; done
cat $R/status14.txt
