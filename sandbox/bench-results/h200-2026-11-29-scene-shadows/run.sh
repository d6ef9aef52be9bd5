#!/bin/bash
# Device run for issues 18 and 20: scene shadows on the street corner; the cobblestone workload's
# phases and the seed port (Tatarchuk's listing 2) beside our POM, θ = 0, 45, 75°.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
nvidia-smi > $R/nvidia-smi.txt 2>&1
./.devbin/sandbox-new bench --out $R/scene-shadows --only scene-shadows --size 1920x1080 --size 3840x2160 > $R/scene-shadows.log 2>&1
./.devbin/sandbox-new render --scene assets/street_corner.glb --size 1920x1080 --debug-view scene_shadow --out $R/street_corner_scene_shadow_h200.png > $R/render.log 2>&1
cp .benchdata/*.png .devbin/ 2>/dev/null
cd .devbin
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for theta in 0 45 75; do
  ./sandbox-new bench --out $R/seed-port-$theta $COB --view-angle $theta --size 3840x2160 --only phases --only seed-port > $R/seed-port-$theta.log 2>&1
done
cd /tmp && tar czf $OUT/results.tgz results
grep -h -E "scene_shadows|phases|seed_port|street corner|seed port" $R/*.log | grep -v "^wrote" | head -80
