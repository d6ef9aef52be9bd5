#!/bin/bash
# Session 19's second device run (issue 32, the CPU side): v7-frames (b80fbb8) against
# v8-old-propagate (last frame's models kept in draw order, looked up by position) and v10-order
# (that, the roots' transforms propagated in one pass, and each material's draws put in last
# frame's sorted order before the sort), three rounds in turn, both paths, cpu-side only.
# run11 had v9 (v10 without the last frame's order): propagating in one pass left the draws
# in spawn order, which 10,000 draws took 3-5 ms a frame to sort.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run12.sh $R/
W=/tmp/w; mkdir -p $W
unpack() { if command -v xz >/dev/null; then xz -dc $1 | tar xf - -C $W
else python3 -c "import lzma,sys;sys.stdout.buffer.write(lzma.open('$1').read())" | tar xf - -C $W; fi; }
unpack .devbin/variants10.tar.xz; unpack .devbin/variants12.tar.xz
cp .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date12.txt
nvidia-smi --query-gpu=name,driver_version --format=csv >> $R/date12.txt 2>&1
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 240 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status12.txt; }
for round in 1 2 3; do
for v in v7-frames v8-old-propagate v10-order; do
  run $v-cpu-r$round ./$v bench $COB --view-angle 45 --only cpu-side --path forward --path deferred
done
done
cd /tmp && tar czf $OUT/results12.tgz r
for f in $R/*-cpu-r*.log; do echo "== $(basename $f)"; grep -h "^CPU" $f | sed 's/CPU, 10000 parallax entities//; s/median ms per frame://; s/render (record + submit)/render/'; done
cat $R/status12.txt
