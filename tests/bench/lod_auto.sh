#!/usr/bin/env bash
# The automatic level of detail against a frame-time target: the viewer's --lod auto --target-ms T
# (runtime/front/host/scene.c: each frame the finest level within a face budget, the budget from a
# moving average of the time per face, updated every frame) over a full turn, per style and target: the median frame time and the
# frames within 10 % of the target after the first 20. Writes a marked section of RESULTS.md.
#   tests/bench/lod_auto.sh [RESULTS.md]        (make bench runs it; make bench-lod-auto alone)
#   AUTO_MODEL (bunny00), AUTO_FRAMES (300), AUTO_TARGETS ("shaded:1 shaded:2 shaded:3 lines:2 lines:4 lines:6")
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
model=${AUTO_MODEL:-bunny00} frames=${AUTO_FRAMES:-300}
targets=${AUTO_TARGETS:-shaded:1 shaded:2 shaded:3 lines:2 lines:4 lines:6}
out=build/bench/lod_auto
name=${model}_auto
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
src=build/models/$model.off
[ -f "$src" ] || make -s "$src"
run make -s view MODEL="$src" NAME="$name" BAKE_OPTS="--as both" >"$out/build.log"
view=build/$name/$name-view
: >"$out/rows.txt"
for st in $targets; do
    style=${st%%:*} t=${st#*:}
    run "$view" --mode "$style" --lod auto --target-ms "$t" --bench "$frames" >"$out/$style-$t.txt"
    run "$view" --mode "$style" --bench "$frames" >"$out/$style-full.txt"
    echo "$style $t" >>"$out/rows.txt"
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$model" "$frames" "$load" >"$out/section.md" <<'PY'
import json, re, sys
out, model, frames, load = sys.argv[1:5]
print("## Automatic level of detail: holding a frame-time target\n")
print(f"`tests/bench/lod_auto.sh` (`make bench`, `make bench-lod-auto`): {model} baked `--as both`, the viewer's "
      f"`--bench {frames}` (a full turn, 320x240) with `--lod auto --target-ms T`: before each frame the finest level "
      "within a face budget (`mc_pmesh_lod_fit`); the budget is the target at the measured time per face of the level "
      "(a moving average over about five frames); the level changes only when the budget moves by more than 4 %. Held: frames after the first 20 whose time is within 10 % of the "
      "target. The full level's median time in the same run is given for scale: a target above it is met by "
      "drawing everything.\n")
print("| style | target ms | median ms | frames held within 10 % | faces drawn per frame | full level's median ms |")
print("|---|---:|---:|---:|---:|---:|")
for line in open(f"{out}/rows.txt"):
    style, t = line.split()
    a = open(f"{out}/{style}-{t}.txt").read()
    full = open(f"{out}/{style}-full.txt").read()
    med = float(re.search(r"ms per frame \(median\): ([\d.]+)", a).group(1))
    held, n = map(int, re.search(r"(\d+) of (\d+) frames after the first 20 within 10 %", a).groups())
    faces = float(re.search(r"faces drawn per frame: ([\d.]+)", a).group(1))
    fmed = float(re.search(r"ms per frame \(median\): ([\d.]+)", full).group(1))
    print(f"| {style} | {float(t):g} | {med:.3f} | {held} of {n} ({100 * held / n:.0f} %) | {faces:,.0f} | {fmed:.3f} |")
print(f"\nLoad average at the end: {load}.")
PY
write_section "$results" lod-auto "$out/section.md" "${cmds[@]}"
