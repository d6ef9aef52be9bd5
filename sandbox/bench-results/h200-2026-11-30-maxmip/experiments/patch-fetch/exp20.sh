#!/bin/bash
# Experiment: max-mip's patch by one gather (sandbox-new) or four loads (sandbox-loads), forward
# and deferred, 4K cobblestones at 45°.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
cp .benchdata/*.png .devbin/ 2>/dev/null
cd .devbin
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for bin in sandbox-new sandbox-loads; do
  timeout 200 ./$bin bench --out $R/$bin $COB --view-angle 45 --size 3840x2160 --only methods --path forward --path deferred > $R/$bin.log 2>&1
done
cd /tmp && tar czf $OUT/results.tgz results
grep -H -E "^methods .*(maxmip|pom )" $R/*.log | head -40
