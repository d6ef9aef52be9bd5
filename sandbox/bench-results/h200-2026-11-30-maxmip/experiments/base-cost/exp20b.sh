#!/bin/bash
# Experiment: the forward march's base cost. sandbox-new = main (gradients, channel per pixel,
# a division per step); sandbox-lean = channel and convention per pipeline + a reciprocal step;
# sandbox-both = lean + height samples at an explicit level. Seed port beside each, θ 0/45/75.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
cp .benchdata/*.png .devbin/ 2>/dev/null
cd .devbin && for g in sandbox-*.gz; do gunzip -f $g; done && chmod +x sandbox-*
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for bin in sandbox-new sandbox-lean sandbox-both; do
  for theta in 0 45 75; do
    timeout 100 ./$bin bench --out $R/$bin-$theta $COB --view-angle $theta --size 3840x2160 --only seed-port --path forward --path deferred > $R/$bin-$theta.log 2>&1
  done
done
cd /tmp && tar czf $OUT/results.tgz results
for f in $R/*.log; do echo "$f"; grep -E "seed_port .*(ours|seed port)$" $f | awk '{print $9, $14, $15, $16, $17}'; done
