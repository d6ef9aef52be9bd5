# The profile scripts' shared part, sourced by resolve-profile/prof.sh and prepass-profile/prof.sh
# with their arguments (BIN [SIZE]): the cobblestone case, and run NAME [VAR=VALUE...], which times
# the deferred phases at 45° with those variables set (and $EXTRA's flags) into $OUT/NAME.
set -u
BIN=$1; SIZE=${2:-3840x2160}; OUT=${OUT:-prof-out}; mkdir -p "$OUT"
COB="--height assets/bench_cobblestone/cobblestone_height.png
  --normal assets/bench_cobblestone/cobblestone_normal.png
  --albedo assets/bench_cobblestone/cobblestone_albedo.png
  --height-scale 0.05 --tiling 4 --min-samples 8 --max-samples 50 --lod-threshold 4
  --shadow-softening 0.58 --shadows soft --projection ortho --light-angle 45"
run() { local name=$1; shift; local s=$(date +%s)
  env "$@" timeout 120 $BIN bench $COB --size $SIZE --view-angle 45 --only phases --path deferred $EXTRA --out "$OUT/$name" > "$OUT/$name.log" 2>&1
  echo "$name rc $? $(( $(date +%s) - s ))s $(grep -E 'deferred (resolve|prepass)' "$OUT/$name.log" | awk "{print \$NF, \$8}" | tr '\n' ' ')" | tee -a "$OUT/summary.txt"; }
