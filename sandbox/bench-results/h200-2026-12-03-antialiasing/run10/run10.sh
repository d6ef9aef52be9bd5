#!/bin/bash
# Session 18's device run (issue 32): v5-vec4 (the TAA pass before, one history with depth in
# alpha) against v7-frames (cd14c7a: a per-pixel frame count in alpha, the depth in its own
# r32float history), three rounds in turn; then v7's CPU side under TAA.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run10.sh $R/
W=/tmp/w; mkdir -p $W
if command -v xz >/dev/null; then xz -dc .devbin/variants10.tar.xz | tar xf - -C $W
else python3 -c "import lzma,sys;sys.stdout.buffer.write(lzma.open('.devbin/variants10.tar.xz').read())" | tar xf - -C $W; fi
cp .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date10.txt
nvidia-smi --query-gpu=name,driver_version --format=csv >> $R/date10.txt 2>&1
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 240 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status10.txt; }
for round in 1 2 3; do
for v in v5-vec4 v7-frames; do
  run $v-45-r$round ./$v bench $COB --shadows soft --view-angle 45 --size 3840x2160 --only antialiasing --path forward --path deferred
done
done
run v7-cpu ./v7-frames bench $COB --view-angle 45 --only cpu-side --path forward --path deferred
cd /tmp && tar czf $OUT/results10.tgz r
for f in $R/*-r*.log; do echo "$(basename $f): $(grep -h 'taa taa' $f | awk '{print $14, $8}' | tr '\n' ' ')"; done
grep -h "^CPU" $R/v7-cpu.log
cat $R/status10.txt
