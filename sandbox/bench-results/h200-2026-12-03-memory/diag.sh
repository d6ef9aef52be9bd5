#!/usr/bin/env bash
# Device run: what grows the process on the NVIDIA driver (allocator arenas or the driver's
# caches), the parallax plane at 1920x1080, 10,000 frames, deferred, one variant per process.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan
if ! ls /usr/share/vulkan/icd.d/*nvidia* >/dev/null 2>&1 && [ -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
mkdir -p /tmp/m $OUT/r
cp -r assets/bricks /tmp/m/bricks
gzip -dc .devbin/sandbox-new.gz > /tmp/sandbox-new; chmod +x /tmp/sandbox-new
cat > /tmp/m/plane.ron <<'RON'
(
    size: (1920, 1080),
    camera: (position: (0.0, 1.2, 1.2), target: (0.0, 0.0, 0.0), fov_degrees: 45.0),
    lights: [Directional(direction: (-0.6, -1.0, -0.4), intensity: 100000.0)],
    entities: [(name: "plane", shape: Some(Plane(size: 2.0)), material: Some(Pom(maps: "bricks")))],
    steps: [Advance(frames: 10000), Capture(name: "end")],
)
RON
run() { # name, env...
  local name=$1; shift
  env "$@" /tmp/sandbox-new run-script --path deferred /tmp/m/plane.ron > $OUT/r/$name.log 2>&1 &
  local pid=$!
  ( start=$(date +%s.%N)
    while kill -0 $pid 2>/dev/null; do
      echo "$(awk -v a=$(date +%s.%N) -v b=$start 'BEGIN{printf "%.1f", a-b}') $(awk '/VmRSS|Threads/{printf "%s ", $2}' /proc/$pid/status 2>/dev/null)"
      sleep 1
    done > $OUT/r/$name.rss ) &
}
run base X=1
run arena1 MALLOC_ARENA_MAX=1
run nocache __GL_SHADER_DISK_CACHE=0
run arena1-nothreads MALLOC_ARENA_MAX=1 __GL_THREADED_OPTIMIZATIONS=0 __GL_SHADER_DISK_CACHE=0
wait
sleep 2
for f in $OUT/r/*.rss; do echo "$f $(wc -l < $f) lines"; awk 'NR%8==1' $f | tr '\n' '|'; echo; done
cd $OUT && tar czf diag.tgz r && rm -rf r
