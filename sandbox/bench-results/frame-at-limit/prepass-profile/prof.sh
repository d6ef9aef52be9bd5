#!/usr/bin/env bash
# Where the prepass (visibility) phase's time goes on a frame of the polygon pass: a release build
# of sandbox with prepass-stops-env.diff applied leaves out, by environment variable, the keys'
# clear (POM_PROFILE_PREPASS_NO_CLEAR), the polygon pass (POM_PROFILE_NO_POLYGONS) and the depth
# pass after them (POM_PROFILE_PREPASS_NO_DEPTH_PASS: the clear's compute pass ends the phase).
# All three left out times an empty compute pass: what the phase's timestamps cost alone.
# The diff applies to 5a00966 (its results: ../run-5/prepass-profile/); since, a frame whose
# every draw the polygon pass finds runs no depth pass (../run-5/depth-clear/ forces it back).
# From the repository root: OUT=prof-out bash prof.sh BIN [SIZE].
source "$(dirname "$0")/../profile-run.sh"
for EXTRA in "" "--depth-offset"; do
  run prepass${EXTRA:+-do} POM_PROFILE_NONE=1
  run no-clear${EXTRA:+-do} POM_PROFILE_PREPASS_NO_CLEAR=1
  run no-polygons${EXTRA:+-do} POM_PROFILE_NO_POLYGONS=1
  run no-depth-pass${EXTRA:+-do} POM_PROFILE_PREPASS_NO_DEPTH_PASS=1
  run clear-only${EXTRA:+-do} POM_PROFILE_NO_POLYGONS=1 POM_PROFILE_PREPASS_NO_DEPTH_PASS=1
  run nothing${EXTRA:+-do} POM_PROFILE_PREPASS_NO_CLEAR=1 POM_PROFILE_NO_POLYGONS=1 POM_PROFILE_PREPASS_NO_DEPTH_PASS=1
done
