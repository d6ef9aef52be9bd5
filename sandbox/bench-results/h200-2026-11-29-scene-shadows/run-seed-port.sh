#!/bin/bash
# Device run for issue 20: the seed port beside our POM, near and far field (base cost),
# cobblestone workload at 4K, θ = 0, 45, 75°.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
nvidia-smi > $R/nvidia-smi.txt 2>&1
cp .benchdata/*.png .devbin/ 2>/dev/null
cd .devbin
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for theta in 0 45 75; do
  ./sandbox-new bench --out $R/seed-port-$theta $COB --view-angle $theta --size 3840x2160 --only seed-port > $R/seed-port-$theta.log 2>&1
done
cd /tmp && tar czf $OUT/results.tgz results
grep -h -E "seed_port|seed port|listing" $R/*.log | grep -v "^wrote" | head -60
