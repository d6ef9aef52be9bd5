#!/usr/bin/env bash
# Device call: 59d5ac4 (new) against 59d5ac4 + quad-exchange.diff (quad), resolve rows; two rounds.
. "$(dirname "$0")/../setup.sh"
run() { local name=$1 b=$2; shift 2; timeout 60 $B/$b bench "$@" --out /tmp/scratch/$b-$name > /tmp/r/y/$b-$name.log 2>&1; echo "$b $name $(grep 'deferred resolve' /tmp/r/y/$b-$name.log | awk '{print $9}' | head -1)" | tee -a /tmp/r/summary.txt; }
for b in new quad new quad; do
  run normal-45 $b $COB --size 3840x2160 --view-angle 45 --method normal --only phases --path deferred
  for a in 0 45 75; do run pom-$a $b $COB --size 3840x2160 --view-angle $a --only phases --path deferred; done
done
tar czf $OUT/r14.tgz -C /tmp r
