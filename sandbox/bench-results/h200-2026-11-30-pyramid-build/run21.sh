#!/bin/bash
# Device run, session 9: max-mip's pyramid rebuilt every frame (both paths), and the phases at
# 45° (both paths) to check that recording the builds in the frame changed nothing else.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
nvidia-smi > $R/nvidia-smi.txt 2>&1
cp .benchdata/*.png .devbin/ 2>/dev/null
cp .devbin/run21.sh $R/
cd .devbin && gunzip -f sandbox-new.gz && chmod +x sandbox-new
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
timeout 200 ./sandbox-new bench --out $R/pyramid $COB --view-angle 45 --size 1920x1080 --only pyramid-build --path forward --path deferred > $R/pyramid.log 2>&1
timeout 200 ./sandbox-new bench --out $R/phases-45 $COB --view-angle 45 --size 3840x2160 --only phases --path forward --path deferred > $R/phases-45.log 2>&1
cd /tmp && tar czf $OUT/results.tgz results
grep -h -E "^pyramid_build|^phases" $R/pyramid.log $R/phases-45.log
grep -h -A3 "side by side" $R/phases-45.log
