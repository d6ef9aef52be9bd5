#!/usr/bin/env bash
# Device call: c6ebfb5 (mid) against new (rows and background as in 59d5ac4, its neighbour rays unprojected, classification workgroups of 2x2 tiles, block-classify.diff: not kept); light-list variants on prof (as in footprint/run.sh).
. "$(dirname "$0")/../setup.sh"
run() { local name=$1 b=$2; shift 2; timeout 60 env POM_PROFILE_WGSL="$EDIT" $B/$b bench "$@" --out /tmp/scratch/$b-$name > /tmp/r/y/$b-$name.log 2>&1; echo "$b $name rc $?" >> /tmp/r/y/summary.txt; }
EDIT=""
for b in mid new mid new; do
  run overdraw $b --path deferred --only overdraw
  run normal-45 $b $COB $K4 --method normal --only phases --path deferred
  run phases-45 $b $COB $K4 --only phases --path deferred
  run scene-shadows $b $K4 --only scene-shadows --path deferred
  cp -r /tmp/r/y /tmp/r/round-$b-$(ls /tmp/r | wc -l); rm -rf /tmp/r/y; mkdir -p /tmp/r/y
done
lights() { local name=$1; for m in normal pom; do run $name-$m prof $COB $K4 --method $m --only phases --path deferred; echo "$name $m $(grep 'deferred resolve' /tmp/r/y/prof-$name-$m.log | awk '{print $9}')" >> /tmp/r/lights.txt; done; }
EDIT=""; lights base
EDIT="if light_clusters[3] == 0u {=>if true {"; lights no-load
EDIT="if light_clusters[3] == 0u {=>if frame.light_counts.y == 0u {"; lights uniform-test
EDIT=""; lights base-again
cp -r /tmp/r/y /tmp/r/lights-logs
tar czf $OUT/r11.tgz -C /tmp r; for d in /tmp/r/round-*; do echo "== $d"; grep -h "3840x2160" $d/*overdraw*.log | grep deferred | awk '{print $9, $16, $17, $18, $19, $20, $21, $22}' | head -6; grep -h "deferred resolve" $d/*45*.log | awk '{print $2, $9}'; grep -h "deferred" $d/*scene-shadows*.log | grep -v "^timing" | awk '{print $9, $NF, $(NF-1), $(NF-2), $(NF-3)}' | head -12; done; cat /tmp/r/lights.txt
