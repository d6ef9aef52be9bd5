#!/bin/bash
# Session 16's device run (issue 32): the antialiasing bench group with TAA's 16x16 tile, the
# object motion numbers (no draw moves in the bench: TAA reads none) and the mip bias (-2).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run7.sh $R/
W=/tmp/w; mkdir -p $W
gunzip -c .devbin/sandbox-aa.gz > $W/sandbox; chmod +x $W/sandbox
cp .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date7.txt
nvidia-smi --query-gpu=name,driver_version --format=csv >> $R/date7.txt 2>&1
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 300 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status7.txt; }
run aa-45 ./sandbox bench $COB --shadows soft --view-angle 45 --size 3840x2160 --only antialiasing --path forward --path deferred
run aa-75 ./sandbox bench $COB --shadows soft --view-angle 75 --size 3840x2160 --only antialiasing --path forward --path deferred
cd /tmp && tar czf $OUT/results7.tgz r
grep -h "antialiasing\|jittered\|mip bias" $R/aa-45.log $R/aa-75.log | head -60
cat $R/status7.txt
