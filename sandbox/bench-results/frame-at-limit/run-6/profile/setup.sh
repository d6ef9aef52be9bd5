# Shared by this folder's device calls (source it from a call's run.sh): the Vulkan loader as in
# sandbox/BENCHMARKS.md, "How to run"; B: a folder holding the release builds a call names (B/old,
# B/new, B/prof, ...), built from the commits its header names. Logs go to /tmp/r/y.
B=${B:?a folder holding the release builds}
mkdir -p /tmp/r/y
export WGPU_BACKEND=vulkan VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
nvidia-smi --query-gpu=name,driver_version --format=csv > /tmp/r/gpu.txt
COB="--height assets/bench_cobblestone/cobblestone_height.png --normal assets/bench_cobblestone/cobblestone_normal.png --albedo assets/bench_cobblestone/cobblestone_albedo.png --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4 --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
K4="--size 3840x2160 --view-angle 45"
# B/prof at 4K, 45°, `--method normal` then POM, with the WGSL edited at composition by $EDIT
# (POM_PROFILE_WGSL: wgsl-hook-env.diff); each resolve median goes to summary.txt.
wgsl_variant() { local name=$1; for m in normal pom; do timeout 60 env POM_PROFILE_WGSL="$EDIT" $B/prof bench $COB $K4 --method $m --only phases --path deferred --out /tmp/scratch/$name-$m > /tmp/r/y/$name-$m.log 2>&1; echo "$name $m rc $? $(grep 'deferred resolve' /tmp/r/y/$name-$m.log | awk '{print $9}')" | tee -a /tmp/r/y/summary.txt; done; }
