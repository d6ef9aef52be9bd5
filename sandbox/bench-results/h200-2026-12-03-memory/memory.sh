#!/usr/bin/env bash
# Device run: resident and GPU memory of headless soaks (old and new builds, both paths, TAA,
# the street corner at 1920x1080, 10,000 frames), then the anti-aliasing bench of both builds.
set -u
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
export WGPU_BACKEND=vulkan
if ! ls /usr/share/vulkan/icd.d/*nvidia* >/dev/null 2>&1 && [ -e /usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json ]; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
mkdir -p /tmp/m $OUT/r
cp assets/street_corner.glb /tmp/m/
cp -r assets/bricks /tmp/m/bricks
cat > /tmp/m/plane.ron <<'RON'
(
    size: (1920, 1080),
    camera: (position: (0.0, 1.2, 1.2), target: (0.0, 0.0, 0.0), fov_degrees: 45.0),
    lights: [Directional(direction: (-0.6, -1.0, -0.4), intensity: 100000.0)],
    entities: [(name: "plane", shape: Some(Plane(size: 2.0)), material: Some(Pom(maps: "bricks")))],
    steps: [
        Advance(frames: 500), Capture(name: "a500"),
        Advance(frames: 3500), Capture(name: "a4000"),
        Advance(frames: 6000), Capture(name: "a10000"),
    ],
)
RON
for b in old new; do gzip -dc .devbin/sandbox-$b.gz > /tmp/sandbox-$b; chmod +x /tmp/sandbox-$b; done
cat > /tmp/m/soak.ron <<'RON'
(
    size: (1920, 1080),
    camera: (position: (0.75, 0.6, 1.6), target: (0.3, 0.0, 0.3), fov_degrees: 40.0, aa: Some(taa)),
    entities: [(name: "corner", gltf: "street_corner.glb")],
    steps: [
        Advance(frames: 500), Capture(name: "a500"),
        Advance(frames: 3500), Capture(name: "a4000"),
        Advance(frames: 6000), Capture(name: "a10000"),
    ],
)
RON
nvidia-smi --query-gpu=name,driver_version --format=csv > $OUT/r/gpu.txt
pids=()
for scene in soak plane; do for b in old new; do for p in forward deferred; do
  name=$scene-$b-$p
  /tmp/sandbox-$b run-script --path $p /tmp/m/$scene.ron > $OUT/r/$name.log 2>&1 &
  pid=$!; pids+=($pid)
  ( start=$(date +%s.%N)
    while kill -0 $pid 2>/dev/null; do
      rss=$(awk '/VmRSS/{print $2}' /proc/$pid/status 2>/dev/null)
      gpu=$(nvidia-smi --query-compute-apps=pid,used_memory --format=csv,noheader,nounits 2>/dev/null | awk -F', ' -v p=$pid '$1==p{print $2}')
      echo "$(awk -v a=$(date +%s.%N) -v b=$start 'BEGIN{printf "%.1f", a-b}') rss_kib=$rss gpu_mib=${gpu:-?} steps=$(grep -c . $OUT/r/$name.log)"
      sleep 2
    done > $OUT/r/$name.rss ) &
done; done; done
for pid in "${pids[@]}"; do wait $pid; done
sleep 3
for b in old new; do
  timeout 150 /tmp/sandbox-$b bench --out /tmp/bench-$b --size 3840x2160 --only antialiasing --path forward --path deferred \
    --height .devbin/cobblestone_height.png --normal .devbin/cobblestone_normal.png --albedo .devbin/cobblestone_albedo.png \
    --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 \
    --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45 --view-angle 45 > $OUT/r/bench-$b.log 2>&1
  cp /tmp/bench-$b/bench.csv $OUT/r/bench-$b.csv 2>/dev/null
done
tail -n 2 $OUT/r/*.rss; tail -n 3 $OUT/r/*.log
cd $OUT && tar czf results.tgz r && rm -rf r
