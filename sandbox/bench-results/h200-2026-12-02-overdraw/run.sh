#!/bin/bash
# Device run of session 14 (issue 30): the old build (eeb1746, main before this session) and
# the new one (a visibility fragment behind the depth its pixel kept is dropped before it
# marches), side by side in one call: the overdraw group twice, alternating, and the
# cobblestone workload at 45 degrees, 4K, both paths, for the "nothing else slower" check.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run.sh $R/
W=/tmp/w; mkdir -p $W
for b in old new; do gunzip -c .devbin/sandbox-$b.gz > $W/sandbox-$b; chmod +x $W/sandbox-$b; done
cp .devbin/cobblestone_*.png $W/
cd $W
nvidia-smi -L > $R/gpu.txt 2>&1; date -u > $R/date.txt
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 200 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status.txt; }
for round in 1 2; do for b in old new; do
  run overdraw-$b-$round ./sandbox-$b bench --path forward --path deferred --only overdraw
done; done
for b in old new; do
  run cobble-$b-45 ./sandbox-$b bench $COB --shadows soft --view-angle 45 --size 3840x2160 --only phases --path forward --path deferred
done
cd /tmp && tar czf $OUT/results.tgz r
cat $R/status.txt
for f in $R/overdraw-*.log; do echo "== $(basename $f)"; grep -h "^overdraw" $f | awk '{print $3, $4, $8, $13, $14, $15, $16, $17, $18, $19, $20}'; done
