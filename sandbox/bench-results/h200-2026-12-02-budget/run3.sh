#!/bin/bash
# Device run 3 of session 13: the CPU side only, three rounds alternating the build before this
# session (old), the one measured in run 1 (new) and the one with the per-draw data made once per
# run of equal materials and the mirror copy of changed entries only (cpu).
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan NODEVICE_SELECT=1
R=/tmp/r3; mkdir -p $R; cp .devbin/run3.sh $R/
W=/tmp/w; mkdir -p $W
for b in old new cpu; do gunzip -c .devbin/sandbox-$b.gz > $W/sandbox-$b; chmod +x $W/sandbox-$b; done
cd $W; date -u > $R/date.txt
for round in 1 2 3; do for b in old new cpu; do
  timeout 100 ./sandbox-$b bench --path forward --path deferred --only cpu-side --out $R/cpu-$b-$round > $R/cpu-$b-$round.log 2>&1; echo "cpu-$b-$round: exit $?"
done; done
cd /tmp && tar czf $OUT/results3.tgz r3
for f in $R/cpu-*.log; do echo "== $(basename $f)"; grep -h "CPU, 10000" $f | sed 's/CPU, 10000 parallax entities //; s/median ms per frame: //'; done
