#!/bin/bash
# Session 20's device run (issue 32): the antialiasing group at 4K, both paths, 45° and 75°,
# with the cobblestones once (tiling 1: magnified, mip 0 whatever the bias) and tiled 8 times
# (minified: the mip biases of TAA and of the post filter read finer levels), build 04c9972
# (POST_FILTER_MIP_BIAS = -1).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan
R=/tmp/r13; mkdir -p $R
cp .devbin/run13.sh $R/
W=/tmp/w; mkdir -p $W
cp .devbin/v11 .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date13.txt
nvidia-smi --query-gpu=name,driver_version --format=csv >> $R/date13.txt 2>&1
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 240 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status13.txt; }
for tiling in 1 8; do
for angle in 45 75; do
  run v11-aa-$angle-t$tiling ./v11 bench $COB --tiling $tiling --shadows soft --view-angle $angle --size 3840x2160 --only antialiasing --path forward --path deferred
done
done
cd /tmp && tar czf $OUT/results13.tgz r13
for f in $R/v11-aa-*.log; do echo "== $(basename $f)"; grep -h "^antialiasing" $f | awk '{printf "%s %s ", $8, $13; for(i=14;i<=NF;i++) printf "%s ", $i; print ""}'; grep -h "mip bias:\|jittered march:" $f; done
cat $R/status13.txt
