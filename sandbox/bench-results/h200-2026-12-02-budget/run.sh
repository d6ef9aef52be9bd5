#!/bin/bash
# Device run of session 13 (issue 30): the old build (fe6e95e, main before this session) and the
# new one, side by side in one call. Part A: the cobblestone workload at 4K, 0/45/75 degrees,
# phases and the seed port, both paths. Part B: the street corner (scene shadows), overdraw and
# the CPU side (old, new, old, new), and the methods and far-field groups for the "nothing else
# slower" check.
set -u
part=$1
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R/$part
cp .devbin/run.sh $R/
W=/tmp/w; mkdir -p $W
for b in old new; do gunzip -c .devbin/sandbox-$b.gz > $W/sandbox-$b; chmod +x $W/sandbox-$b; done
cp .devbin/cobblestone_*.png $W/
cd $W
nvidia-smi -L > $R/gpu.txt 2>&1; date -u > $R/date-$part.txt
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 200 "$@" --out $R/$part/$name > $R/$part/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/$part/status.txt; }
if [ "$part" = A ]; then
  for a in 0 45 75; do for b in old new; do
    run cobble-$b-$a ./sandbox-$b bench $COB --shadows soft --view-angle $a --size 3840x2160 --only phases --only seed-port --path forward --path deferred
  done; done
  # Where the new resolve's time goes, at 45 degrees: without the self-shadow ray (the seed port
  # without its own), and without the march (normal mapping: rebuilding and shading the pixel).
  run attrib-noshadow ./sandbox-new bench $COB --shadows off --view-angle 45 --size 3840x2160 --only phases --only seed-port --path deferred
  run attrib-normal ./sandbox-new bench $COB --shadows soft --method normal --view-angle 45 --size 3840x2160 --only phases --path deferred
else
  for b in old new; do
    run street-$b ./sandbox-$b bench --path forward --path deferred --view-angle 45 --only scene-shadows --only overdraw
  done
  for round in 1 2; do for b in old new; do
    run cpu-$b-$round ./sandbox-$b bench --path forward --path deferred --only cpu-side
  done; done
  for b in old new; do
    run others-$b ./sandbox-$b bench --path forward --path deferred --size 3840x2160 --view-angle 45 --only methods --only far-field
  done
fi
cd /tmp && tar czf $OUT/results-$part.tgz r
cat $R/$part/status.txt
