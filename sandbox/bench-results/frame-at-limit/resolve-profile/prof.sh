#!/usr/bin/env bash
# Where the resolve's time goes: a release build of sandbox with profile-stops-env.diff applied
# reads POM_PROFILE_STOP (1: after finding the pixel, 2: after rebuilding it, 3: after the view
# ray, 4: the maps only, 5: no lights, 6: no light clusters), POM_PROFILE_NO_BACKGROUND and
# POM_PROFILE_NO_CANDIDATES; and for the visibility pass POM_PROFILE_VISIBILITY_NO_ATOMIC (its
# fragments merge no key: raster and depth alone) and POM_PROFILE_VISIBILITY_DEPTH=no-write|off.
# From the repository root: OUT=prof-out bash prof.sh BIN [SIZE].
source "$(dirname "$0")/../profile-run.sh"
EXTRA=""
run visibility-again POM_PROFILE_STOP=0
run visibility-no-atomic POM_PROFILE_VISIBILITY_NO_ATOMIC=1
run visibility-no-depth-write POM_PROFILE_VISIBILITY_DEPTH=no-write
run visibility-no-depth POM_PROFILE_VISIBILITY_DEPTH=off
run visibility-no-atomic-no-depth POM_PROFILE_VISIBILITY_NO_ATOMIC=1 POM_PROFILE_VISIBILITY_DEPTH=off
for method in normal pom; do
  EXTRA=""; [ $method = normal ] && EXTRA="--method normal"
  for stop in 0 1 2 3 4 5 6; do
    [ $method = pom ] && [ $stop -ge 4 ] && continue
    run $method-stop$stop POM_PROFILE_STOP=$stop
  done
  run $method-nobg POM_PROFILE_NO_BACKGROUND=1
  run $method-nocand POM_PROFILE_NO_CANDIDATES=1
  run $method-stop1-nobg-nocand POM_PROFILE_STOP=1 POM_PROFILE_NO_BACKGROUND=1 POM_PROFILE_NO_CANDIDATES=1
  run $method-again POM_PROFILE_STOP=0
done
