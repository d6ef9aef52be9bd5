#!/bin/bash
# Third device run of session 14 (issue 31): "early" (run2.sh's second build) against "clip"
# (a silhouette without depth offset no longer exports its depth from the prepass and the
# visibility pass: the rasterizer writes the polygon's), side by side: the silhouette group,
# the street corner, and the overdraw group (depth offset keeps its entry points).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run3.sh $R/
W=/tmp/w; mkdir -p $W
for b in early clip; do gunzip -c .devbin/sandbox-$b.gz > $W/sandbox-$b; chmod +x $W/sandbox-$b; done
cp .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date3.txt
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 240 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status3.txt; }
for b in early clip; do
  run silhouette-$b ./sandbox-$b bench $COB --shadows soft --view-angle 45 --size 3840x2160 --only silhouette --path forward --path deferred
  run street-$b ./sandbox-$b bench --path forward --path deferred --view-angle 45 --size 3840x2160 --only scene-shadows
done
run overdraw-clip ./sandbox-clip bench --path forward --path deferred --only overdraw
cd /tmp && tar czf $OUT/results3.tgz r
for b in early clip; do echo "== $b"; grep -h "silhouette:" $R/silhouette-$b.log; grep -h "^silhouette" $R/silhouette-$b.log | awk '{print $13, $14, $15, $16, $9}'; grep -h "scene_shadows" $R/street-$b.log | grep "deferred\|forward" | grep "frame\|prepass" | awk '{print $13, $14, $15, $16, $17, $18, $9}'; done
grep -h "overdraw:" $R/overdraw-clip.log
