#!/bin/bash
# Device run, issue 27: the bench command that found no GPU after a few dozen apps (point 3),
# run from a folder that is not the repository (point 4), then the headline figures for
# BENCHMARKS.md: the cobblestone workload's phases and the seed port at 4K, 0/45/75 degrees,
# both paths.
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/results; mkdir -p $R
nvidia-smi > $R/nvidia-smi.txt 2>&1
cp .devbin/run27.sh $R/
mkdir -p /tmp/elsewhere
gunzip -c .devbin/sandbox.gz > /tmp/elsewhere/sandbox && chmod +x /tmp/elsewhere/sandbox
cp .benchdata/*.png /tmp/elsewhere/
cd /tmp/elsewhere
start=$(date +%s)
timeout 300 ./sandbox bench --path forward --path deferred --view-angle 45 --only scene-shadows --only overdraw --only cpu-side --out $R/repro > $R/repro.log 2>&1
echo "repro exit status $? after $(( $(date +%s) - start )) s" | tee -a $R/repro.log
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
for a in 0 45 75; do
  timeout 100 ./sandbox bench --out $R/head-$a $COB --view-angle $a --size 3840x2160 --only phases --only seed-port --path forward --path deferred > $R/head-$a.log 2>&1
  echo "angle $a exit status $?" | tee -a $R/head-$a.log
done
cd /tmp && tar czf $OUT/results.tgz results
grep -h -E "^(scene_shadows|cpu_side|overdraw)" $R/repro.log | head -40
for a in 0 45 75; do grep -h -E "^(phases|seed_port)" $R/head-$a.log; grep -h -A3 "side by side" $R/head-$a.log; done
