#!/bin/bash
# Device run 2 of session 11: the CPU side of 10,000 parallax entities, this tree against the
# last session's (2a71b8c), interleaved three times on one machine.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan
gunzip -c .devbin/sandbox.gz > /tmp/new; gunzip -c .devbin/sandbox-old.gz > /tmp/old; chmod +x /tmp/new /tmp/old
mkdir -p $OUT/r; cd /tmp
for i in 1 2 3; do
  for b in new old; do
    /tmp/$b bench --size 1920x1080 --path forward --path deferred --only cpu-side --out $OUT/r/$b$i > $OUT/r/$b$i.log 2>&1
  done
done
grep -h "CPU, 10000" $OUT/r/*.log > $OUT/r/summary.txt
cd $OUT && tar czf results.tgz r && rm -rf r
