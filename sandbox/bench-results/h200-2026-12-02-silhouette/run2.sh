#!/bin/bash
# Second device run of session 14 (issue 31): the silhouette group and the street corner with
# the build of run.sh ("new": every depth-pass fragment of a clipping material marches) and
# the next one ("early": the depth passes march only where a ray could leave the surface),
# side by side; and the overdraw group with "early" (depth offset marches as before).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run2.sh $R/
W=/tmp/w; mkdir -p $W
for b in new early; do gunzip -c .devbin/sandbox-$b.gz > $W/sandbox-$b; chmod +x $W/sandbox-$b; done
cp .devbin/cobblestone_*.png $W/
cd $W
nvidia-smi -L > $R/gpu.txt 2>&1; date -u > $R/date2.txt
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 240 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status2.txt; }
for b in new early; do
  run silhouette-$b ./sandbox-$b bench $COB --shadows soft --view-angle 45 --size 3840x2160 --only silhouette --path forward --path deferred
  run street-$b ./sandbox-$b bench --path forward --path deferred --view-angle 45 --size 3840x2160 --only scene-shadows
done
run overdraw-early ./sandbox-early bench --path forward --path deferred --only overdraw
cd /tmp && tar czf $OUT/results2.tgz r
cat $R/status2.txt
for b in new early; do echo "== $b"; grep -h "^silhouette" $R/silhouette-$b.log | awk '{print $12, $14, $15, $16}'; grep -h "silhouette:" $R/silhouette-$b.log; grep -h "deferred  frame\|forward  frame" $R/street-$b.log | awk '{print $12, $14, $15, $16, $17}'; done
grep -h "overdraw:" $R/overdraw-early.log
