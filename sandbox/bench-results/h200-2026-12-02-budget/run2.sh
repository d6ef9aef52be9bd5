#!/bin/bash
# Device run 2 of session 13: the seed port's compute pass after its corners stopped being an
# array, at 4K and 0/45/75 degrees beside our resolve (new build only), with and without soft
# shadows.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r2; mkdir -p $R; cp .devbin/run2.sh $R/
W=/tmp/w; mkdir -p $W; gunzip -c .devbin/sandbox-new.gz > $W/sandbox; chmod +x $W/sandbox
cp .devbin/cobblestone_*.png $W/; cd $W; date -u > $R/date.txt
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
for a in 0 45 75; do
  timeout 120 ./sandbox bench $COB --shadows soft --view-angle $a --size 3840x2160 --only phases --only seed-port --path deferred --out $R/seed-$a > $R/seed-$a.log 2>&1; echo "seed-$a: exit $?"
done
timeout 120 ./sandbox bench $COB --shadows off --view-angle 45 --size 3840x2160 --only seed-port --path deferred --out $R/seed-noshadow > $R/seed-noshadow.log 2>&1; echo "seed-noshadow: exit $?"
cd /tmp && tar czf $OUT/results2.tgz r2
grep -h "seed port compute\|resolve / seed" $R/*.log
