#!/bin/bash
# Session 19's device run (issue 32). The CPU side of following models: v7-frames (b80fbb8:
# two SipHash maps of entity -> model, filled and swapped every TAA frame) against v9-secant
# (last frame's models kept in draw order, looked up by position; roots' transforms propagated
# in one pass; the secant_steps parameter) and v8-old-propagate (v9 without secant_steps and
# with b80fbb8's propagate_transforms, to time that part alone: v7 has no transforms column),
# three rounds in turn, both paths, cpu-side only. Then v9's antialiasing group at 4K, 45° and
# 75° (the jittered march with 1 and 3 secant steps against 50 plain samples).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r; mkdir -p $R
cp .devbin/run11.sh $R/
W=/tmp/w; mkdir -p $W
unpack() { if command -v xz >/dev/null; then xz -dc $1 | tar xf - -C $W
else python3 -c "import lzma,sys;sys.stdout.buffer.write(lzma.open('$1').read())" | tar xf - -C $W; fi; }
unpack .devbin/variants10.tar.xz; unpack .devbin/variants11.tar.xz
cp .devbin/cobblestone_*.png $W/
cd $W
date -u > $R/date11.txt
nvidia-smi --query-gpu=name,driver_version --format=csv >> $R/date11.txt 2>&1
nproc >> $R/date11.txt; grep -m1 "model name" /proc/cpuinfo >> $R/date11.txt
COB="--height cobblestone_height.png --normal cobblestone_normal.png --albedo cobblestone_albedo.png --height-scale 0.05 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --projection ortho --light-angle 45"
run() { local name=$1; shift; local start=$(date +%s); timeout 240 "$@" --out $R/$name > $R/$name.log 2>&1; echo "$name: exit $? after $(( $(date +%s) - start )) s" | tee -a $R/status11.txt; }
for round in 1 2 3; do
for v in v7-frames v9-secant v8-old-propagate; do
  run $v-cpu-r$round ./$v bench $COB --view-angle 45 --only cpu-side --path forward --path deferred
done
done
for angle in 45 75; do
  run v9-aa-$angle ./v9-secant bench $COB --shadows soft --view-angle $angle --size 3840x2160 --only antialiasing --path forward --path deferred
done
cd /tmp && tar czf $OUT/results11.tgz r
for f in $R/*-cpu-r*.log; do echo "== $(basename $f)"; grep -h "^CPU" $f | sed 's/CPU, 10000 parallax entities//; s/median ms per frame://; s/render (record + submit)/render/'; done
for a in 45 75; do echo "== aa $a"; grep -h "taa, \|jittered march:" $R/v9-aa-$a.log; done
cat $R/status11.txt
