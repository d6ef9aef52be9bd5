#!/bin/bash
# Device run of session 14 (issues 30 and 31): the old build (eeb1746), the new one, and a
# variant of the new one whose visibility fragments read the depth their pixel kept with a
# plain load instead of an atomic one ("plain"): the overdraw group once each; the street corner
# with and without scene shadows, old and new (the new scene's crate and sign clip their
# outlines, uv_bounds); and the silhouette group (the cube and the sphere, each mode) with the
# cobblestone maps at 45 degrees, 4K, both paths.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run.sh $R/
W=/tmp/w; mkdir -p $W
for b in old new plain; do gunzip -c .devbin/sandbox-$b.gz > $W/sandbox-$b; chmod +x $W/sandbox-$b; done
cp .devbin/cobblestone_*.png $W/
cd $W
nvidia-smi -L > $R/gpu.txt 2>&1; date -u > $R/date.txt
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 240 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status.txt; }
for b in old new plain; do
  run overdraw-$b ./sandbox-$b bench --path forward --path deferred --only overdraw
done
for b in old new; do
  run street-$b ./sandbox-$b bench --path forward --path deferred --view-angle 45 --size 3840x2160 --only scene-shadows
done
run silhouette ./sandbox-new bench $COB --shadows soft --view-angle 45 --size 3840x2160 --only silhouette --path forward --path deferred
cd /tmp && tar czf $OUT/results.tgz r
cat $R/status.txt
for f in $R/overdraw-*.log; do echo "== $(basename $f)"; grep -h "depth offset" $f | grep -v "^planes" | awk '{print $4, $8, $13, $14, $15, $16, $17, $18, $19, $20}'; grep -h "deferred:" $f; done
grep -h "frame\|/ " $R/street-*.log | grep -v "^\s*$" | head -40
grep -h "silhouette" $R/silhouette.log | head -30
