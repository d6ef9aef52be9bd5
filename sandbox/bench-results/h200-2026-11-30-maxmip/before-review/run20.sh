#!/bin/bash
# Device run for issue 20 (final build): the method table (steep, POM, relief at 8-64 samples;
# max-mip) and the seed port in the same bench run, forward and deferred, at θ = 45° and 75°;
# every method × shadow mode at 45° both paths; the phases at 0/45/75° both paths (cobblestone
# workload, 4K, soft shadows); 1080p renders of max-mip and POM both ways.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
nvidia-smi > $R/nvidia-smi.txt 2>&1
cp .benchdata/*.png .devbin/ 2>/dev/null
cp .devbin/run20.sh $R/
cd .devbin && gunzip -f sandbox-new.gz && chmod +x sandbox-new
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for theta in 45 75; do
  timeout 280 ./sandbox-new bench --out $R/table-$theta $COB --view-angle $theta --size 3840x2160 --only method-table --only seed-port --path forward --path deferred > $R/table-$theta.log 2>&1
done
timeout 200 ./sandbox-new bench --out $R/methods-45 $COB --view-angle 45 --size 3840x2160 --only methods --path forward --path deferred > $R/methods-45.log 2>&1
for theta in 0 45 75; do
  timeout 150 ./sandbox-new bench --out $R/phases-$theta $COB --view-angle $theta --size 3840x2160 --only phases --path forward --path deferred > $R/phases-$theta.log 2>&1
done
COBR="${COB/--shadows soft /}"
for path in forward deferred; do
  for method in maxmip pom; do
    timeout 60 ./sandbox-new render $COBR --method $method --shadows hard --view-angle 60 --size 1920x1080 --path $path --out $R/$method-hard-60-$path.png > $R/render-$method-$path.log 2>&1
  done
done
cd /tmp && tar czf $OUT/results.tgz results
grep -h -E "^\| |/ the seed" $R/table-*.log
grep -h -E "^methods" $R/methods-45.log
grep -h -E "forward|deferred" $R/phases-*.log | grep -v "^phases" | head -20
