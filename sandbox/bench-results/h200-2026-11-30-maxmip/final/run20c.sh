#!/bin/bash
# Device run for issue 20 after the review fixes: the method table and the seed port at θ = 0,
# 45 and 75° (both paths), max-mip in the methods measurement at 45° (both paths).
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
nvidia-smi > $R/nvidia-smi.txt 2>&1
cp .benchdata/*.png .devbin/ 2>/dev/null
cp .devbin/run20c.sh $R/
cd .devbin && gunzip -f sandbox-new.gz && chmod +x sandbox-new
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for theta in 0 45 75; do
  timeout 200 ./sandbox-new bench --out $R/table-$theta $COB --view-angle $theta --size 3840x2160 --only method-table --only seed-port --path forward --path deferred > $R/table-$theta.log 2>&1
done
timeout 200 ./sandbox-new bench --out $R/methods-45 $COB --view-angle 45 --size 3840x2160 --only methods --path forward --path deferred > $R/methods-45.log 2>&1
cd /tmp && tar czf $OUT/results.tgz results
grep -h -E "maxmip|/ the seed" $R/table-*.log
grep -h -E "^methods +(maxmip|pom)" $R/methods-45.log
