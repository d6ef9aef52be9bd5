#!/bin/bash
# The same as run20.sh's first bench, at θ = 0°.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
cp .benchdata/*.png .devbin/ 2>/dev/null
cp .devbin/run20-0.sh $R/
cd .devbin && gunzip -f sandbox-new.gz && chmod +x sandbox-new
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
timeout 280 ./sandbox-new bench --out $R/table-0 $COB --view-angle 0 --size 3840x2160 --only method-table --only seed-port --path forward --path deferred > $R/table-0.log 2>&1
cd /tmp && tar czf $OUT/results.tgz results
grep -h -E "^\| |/ the seed|^seed_port" $R/table-0.log
