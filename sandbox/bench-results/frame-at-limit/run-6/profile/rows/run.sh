#!/usr/bin/env bash
# Device call: c6ebfb5 (mid) against new (rows and background as in 59d5ac4, its neighbour rays unprojected as in c6ebfb5), changed rows.
. "$(dirname "$0")/../setup.sh"
run() { local name=$1 b=$2; shift 2; timeout 60 $B/$b bench "$@" --out /tmp/scratch/$b-$name > /tmp/r/y/$b-$name.log 2>&1; echo "$b $name rc $?" >> /tmp/r/y/summary.txt; }
for b in mid new mid new; do
  run overdraw $b --path deferred --only overdraw
  run normal-45 $b $COB $K4 --method normal --only phases --path deferred
  run phases-45 $b $COB $K4 --only phases --only seed-port --path deferred
  run depth-offset-45 $b $COB $K4 --depth-offset --only phases --path deferred
  run scene-shadows $b $K4 --only scene-shadows --path deferred
  cp -r /tmp/r/y /tmp/r/round-$b-$(ls /tmp/r | wc -l); rm -rf /tmp/r/y; mkdir -p /tmp/r/y
done
tar czf $OUT/r9.tgz -C /tmp r; for d in /tmp/r/round-*; do echo "== $d"; grep -h "3840x2160" $d/*overdraw*.log | grep deferred | awk '{print $9, $16, $17, $18, $19, $20, $21, $22}' | head -6; grep -h "deferred " $d/*45*.log | grep -v overdraw | awk '{print $2, $9, $16, $17, $18}' | head -12; done
