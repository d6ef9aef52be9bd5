#!/bin/bash
# Device run of session 11: the first use of a pipeline variant (issue 29's "before"), and the
# headline workloads again after the renderer's restructuring.
set -u
R=$(pwd)
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan
gunzip -c .devbin/sandbox.gz > /tmp/sandbox; chmod +x /tmp/sandbox
mkdir -p $OUT/r; cd /tmp
nvidia-smi -L > $OUT/r/gpu.txt 2>&1; nvidia-smi --query-gpu=driver_version --format=csv >> $OUT/r/gpu.txt 2>&1
date -u > $OUT/r/date.txt
/tmp/sandbox bench --size 1920x1080 --size 3840x2160 --only first-use --path forward --path deferred --out $OUT/r/first-use > $OUT/r/first-use.log 2>&1
C="--height $R/.benchdata/cobblestone_height.png --normal $R/.benchdata/cobblestone_normal.png --albedo $R/.benchdata/cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for a in 45; do
  /tmp/sandbox bench --size 3840x2160 --only phases --only seed-port --path forward --path deferred --view-angle $a $C --out $OUT/r/cobble$a > $OUT/r/cobble$a.log 2>&1
done
/tmp/sandbox bench --size 3840x2160 --path forward --path deferred --view-angle 45 --only scene-shadows --only cpu-side --out $OUT/r/street > $OUT/r/street.log 2>&1
cd $OUT && tar czf results.tgz r && rm -rf r
