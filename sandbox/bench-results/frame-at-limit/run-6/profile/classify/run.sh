#!/usr/bin/env bash
# Device call: profile of the classification and the background pass (c6ebfb5 + profile env hooks).
. "$(dirname "$0")/../setup.sh"
run() { local name=$1 b=$2; shift 2; timeout 60 env $ENVS $B/$b bench "$@" --out /tmp/scratch/$b-$name > /tmp/r/y/$b-$name.log 2>&1; echo "$b $name rc $?" >> /tmp/r/y/summary.txt; }
ENVS="X=1"; run overdraw prof --path deferred --only overdraw
ENVS="POM_PROFILE_CLASSIFY_TWICE=1"; run overdraw-twice prof --path deferred --only overdraw
ENVS="POM_PROFILE_FIRST=plain"; run overdraw-first-plain prof --path deferred --only overdraw
ENVS="POM_PROFILE_FIRST=noatomic"; run overdraw-first-noatomic prof --path deferred --only overdraw
ENVS="POM_PROFILE_FIRST=nocand"; run overdraw-first-nocand prof --path deferred --only overdraw
ENVS="POM_PROFILE_FIRST=noatomic,nocand"; run overdraw-first-noatomic-nocand prof --path deferred --only overdraw
ENVS="POM_PROFILE_NO_BACKGROUND=1"; run overdraw-nobg prof --path deferred --only overdraw
ENVS="X=1"; run normal-45 prof $COB $K4 --method normal --only phases --path deferred
ENVS="POM_PROFILE_NO_BACKGROUND=1"; run normal-45-nobg prof $COB $K4 --method normal --only phases --path deferred
ENVS="X=1"; run phases-45 prof $COB $K4 --only phases --path deferred
ENVS="POM_PROFILE_NO_BACKGROUND=1"; run phases-45-nobg prof $COB $K4 --only phases --path deferred
ENVS="X=1"; run overdraw-again prof --path deferred --only overdraw
tar czf $OUT/r6.tgz -C /tmp r; cat /tmp/r/y/summary.txt; for f in /tmp/r/y/*overdraw*.log; do echo "== $f"; grep "3840x2160" $f | grep deferred | awk '{print $9, $16, $17, $18, $19, $20, $21, $22}'; done; grep -h "deferred " /tmp/r/y/*45*.log | head -40
