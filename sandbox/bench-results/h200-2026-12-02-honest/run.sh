#!/bin/bash
# Device run of session 12: issue 30's honest figures, before its performance work. The street
# corner at 4K with each light type against its own baseline, and the CPU side of 10,000
# parallax entities with 0 %, 10 % and 100 % of them turning every frame; both paths.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan
gunzip -c .devbin/sandbox.gz > /tmp/sandbox; chmod +x /tmp/sandbox
mkdir -p $OUT/r; cd /tmp
nvidia-smi -L > $OUT/r/gpu.txt 2>&1; nvidia-smi --query-gpu=driver_version --format=csv >> $OUT/r/gpu.txt 2>&1
date -u > $OUT/r/date.txt
/tmp/sandbox bench --size 3840x2160 --path forward --path deferred --view-angle 45 --only scene-shadows --only cpu-side --out $OUT/r/street > $OUT/r/street.log 2>&1
cd $OUT && tar czf results.tgz r && rm -rf r
