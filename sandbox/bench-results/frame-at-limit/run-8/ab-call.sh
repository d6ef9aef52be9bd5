#!/usr/bin/env bash
# Device call: the issue-50 table at the end, old (3a6df78, before issue 50) against new
# (8ced6dd), every case on each build in turn; tarred into $OUT/ab.tgz.
# The Vulkan loader as in sandbox/BENCHMARKS.md, "How to run"; B: a folder holding the release
# builds B/old and B/new, built from the commits above.
B=${B:?a folder holding the release builds}
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
mkdir -p /tmp/ab; nvidia-smi --query-gpu=name,driver_version --format=csv,noheader > /tmp/ab/gpu.txt 2>&1
( sleep ${STOP:-560}; tar czf $OUT/ab.tgz -C /tmp ab ) &
LIMIT=${LIMIT:-100} OUT=/tmp/ab bash sandbox/bench-results/frame-at-limit/ab.sh $B/old $B/new
tar czf $OUT/ab.tgz -C /tmp ab; kill %1 2>/dev/null; cat /tmp/ab/summary.txt
