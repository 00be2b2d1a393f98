#!/usr/bin/env bash
# The line walk's steps as branches (MC_LINE_SELECT 0) and as masks (1, the default on x86-64), side
# by side in one run, on the tracker's filter step (tests/bench/track_frames.c: the synthetic cube,
# 300 particles, 320x180, one layer, 6-DOF): wall ms per frame (median of rounds, each round
# branches then masks, the order swapped every round), callgrind instructions of mc_filter_step and
# mispredicted branches (cachegrind's branch simulator), and the two builds' poses compared.
# Replaces its marked section of RESULTS.md (make bench-track runs it):
#   tests/bench/line_select.sh [RESULTS.md]
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/common.sh
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
rounds=${LINE_SELECT_ROUNDS:-9}
out=build/bench/line_select
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
args=(--particles 300 --fresh 100 --size 320x180 --dof 6)
for s in 0 1; do
    # shellcheck disable=SC2046
    run $(track_frames_cc "$out/frames$s" -DMC_LINE_SELECT=$s)
    run valgrind --tool=callgrind --toggle-collect=mc_filter_step --callgrind-out-file="$out/cg$s.out" \
        "$out/frames$s" "${args[@]}" --frames 20 >"$out/cg$s.txt" 2>"$out/cg$s.log"
    run valgrind --tool=cachegrind --branch-sim=yes --cache-sim=no --cachegrind-out-file="$out/bs$s.out" \
        "$out/frames$s" "${args[@]}" --frames 20 >/dev/null 2>"$out/bs$s.log"
done
# the same poses, frame by frame (and so the same errors)
"$out/frames0" "${args[@]}" --poses | grep '^pose ' >"$out/poses0.txt"
"$out/frames1" "${args[@]}" --poses | grep '^pose ' >"$out/poses1.txt"
[ -s "$out/poses0.txt" ] && cmp -s "$out/poses0.txt" "$out/poses1.txt" && same=yes || same=no
: >"$out/times.txt"
ms() { "$out/frames$1" "${args[@]}" | sed -n 's/^ms per frame (median) //p'; }
for r in $(seq 1 "$rounds"); do
    if [ $((r % 2)) = 1 ]; then b=$(ms 0); m=$(ms 1); else m=$(ms 1); b=$(ms 0); fi
    echo "$b $m" >>"$out/times.txt"
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$same" "$load" "$rounds" "${args[*]}" >"$out/section.md" <<'PY'
import re, statistics, sys
out, same, load, rounds, args = sys.argv[1:6]
def ir(s):
    m = re.search(r"refs:\s+([\d,]+)", open(f"{out}/cg{s}.log").read())
    return int(m.group(1).replace(",", "")) / 20
def mispredicts(s):
    m = re.search(r"Mispredicts:\s+([\d,]+)", open(f"{out}/bs{s}.log").read())
    return int(m.group(1).replace(",", "")) / 20
rows = [list(map(float, l.split())) for l in open(f"{out}/times.txt")]
med = lambda k: statistics.median(r[k] for r in rows)
ratio = statistics.median(r[0] / r[1] for r in rows)
print("## Line walk: branches or masks\n")
print(f"`tests/bench/line_select.sh` (`make bench-track`): the tracker's filter step (`tests/bench/track_frames.c {args}`: "
      f"the synthetic cube, one layer) with the runtime built with `-DMC_LINE_SELECT=0` (a branch each for the walk's minor "
      f"coordinate and depth steps, the default on Cortex-M) and `=1` (masks, the default on x86-64); {rounds} rounds, each "
      f"both builds (the order swapped every round): wall ms = median over rounds of each run's median frame. "
      f"Instructions: callgrind, `mc_filter_step` only, per frame over 20 frames; mispredicted branches: cachegrind's "
      f"branch simulator, the whole program, per frame over 20 frames. The same estimate in every frame in both builds (`--poses`): **{same}**.\n")
print("| line walk | Ir per frame | mispredicted branches per frame | wall ms per frame |")
print("|---|---:|---:|---:|")
print(f"| branches (MC_LINE_SELECT 0) | {ir(0) / 1e6:.2f} M | {mispredicts(0):,.0f} | {med(0):.3f} |")
print(f"| masks (MC_LINE_SELECT 1, default on x86-64) | {ir(1) / 1e6:.2f} M | {mispredicts(1):,.0f} | {med(1):.3f} |")
print()
print(f"Branches / masks, wall ms (median over rounds of the ratio in the same round): {ratio:.2f}.")
print("Per round (branches / masks ms): " + "; ".join(" / ".join(f"{v:.3f}" for v in r) for r in rows) + ".")
print(f"Load average at the end: {load}.")
PY
write_section "$results" line-select "$out/section.md" "${cmds[@]}" \
    "$out/frames0 ${args[*]}; $out/frames1 ${args[*]}   # per round, $rounds rounds, the order swapped every round"
