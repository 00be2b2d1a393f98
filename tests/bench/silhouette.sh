#!/usr/bin/env bash
# Silhouettes: recall of the probabilistic search against its work, on a turning mesh. For each mesh
# (full level, 320x240, yaw steps of SIL_DEG degrees, pitch 20), tests/gen/sil_check.c runs
# mc_sil_search at each budget (edge tests per frame; seeds a tenth of it) with frame coherence on and
# mc_sil_exact, both with a vertex cache (mc_sil_cache), mc_sil_exact without, and the exact set as
# the lines style finds it (sil_check MODE lines: its projection, facing and edge passes); recall =
# the screen length of the silhouette edges found over the exact set's, per frame after the first
# 10; instructions: callgrind, mc_sil_search / mc_sil_exact / mc_mesh_lines_sparse alone.
# Writes a marked section of RESULTS.md and tests/bench/silhouette.png (recall against the
# instructions as a fraction of the exact scan's: the Pareto front of the search).
#   tests/bench/silhouette.sh [RESULTS.md]      (make bench runs it; make bench-silhouette alone)
#   SIL_MODELS ("bunny00 fandisk"), SIL_BUDGETS ("2000 5000 10000 15000 20000 30000"), SIL_FRAMES (60),
#   SIL_DEG (2)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
models=${SIL_MODELS:-bunny00 fandisk} budgets=${SIL_BUDGETS:-2000 5000 10000 15000 20000 30000}
frames=${SIL_FRAMES:-60} deg=${SIL_DEG:-2}
out=build/bench/silhouette
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
: >"$out/rows.txt"
for m in $models; do
    src=build/models/$m.off
    [ -f "$src" ] || make -s "$src"
    run build/bin/modelc "$src" -o "$out" --name "$m" --depth 5 --as both -q
    run gcc -O2 -g -std=c99 -Wall -Wextra -Iruntime/include "-DPM=mc_pmesh_$m" -include "$out/$m/$m.h" \
        -o "$out/$m-sil" tests/gen/sil_check.c \
        runtime/src/{silhouette,pmesh,mesh_render,mesh_lines,mesh_creases,line,raster,sdepth,xform,xform_vertex,target,fixed,trig,sintab}.c \
        "$out/$m"/*.c -lm
    for b in $budgets exact plain lines; do
        case $b in
            exact) mode="exact cache" fn=mc_sil_exact args="0 0" ;;
            plain) mode=exact fn=mc_sil_exact args="0 0" ;;
            lines) mode=lines fn=mc_mesh_lines_sparse args="0 0" ;;
            *) mode="search cache" fn=mc_sil_search args="$b $((b / 10))" ;;
        esac
        # shellcheck disable=SC2086
        run valgrind --tool=callgrind --toggle-collect=$fn --callgrind-out-file="$out/$m.$b.cg" \
            "$out/$m-sil" run 320 240 "$frames" "$deg" $args $mode >"$out/$m.$b.txt" 2>"$out/$m.$b.log"
        echo "$m $b" >>"$out/rows.txt"
    done
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
python3 - "$out" "$frames" "$deg" "$load" >"$out/section.md" <<'PY'
import re, sys
out, frames, deg, load = sys.argv[1:5]
rows = [l.split() for l in open(f"{out}/rows.txt")]
def parse(m, b):
    t = open(f"{out}/{m}.{b}.txt").read()
    r = dict(zip(["median", "p5", "min", "tests", "facings"], map(float, re.search(
        r"recall median ([\d.]+) p5 ([\d.]+) min ([\d.]+) tests ([\d.]+) facings ([\d.]+)", t).groups())))
    r["faces"] = int(re.search(r"faces (\d+)", t).group(1))
    r["edges"] = int(re.search(r"edges (\d+)", t).group(1))
    r["n"] = int(re.search(r"frames (\d+)", t).group(1)) + 10
    r["ir"] = int(re.search(r"refs:\s+([\d,]+)", open(f"{out}/{m}.{b}.log").read()).group(1).replace(",", "")) / r["n"]
    return r
print("## Silhouettes: the probabilistic search against the exact scan\n")
print(f"`tests/bench/silhouette.sh` (`make bench`, `make bench-silhouette`): the full level at 320x240 turning {deg} "
      f"degrees a frame (pitch 20), {frames} frames; `mc_sil_search` (runtime/src/silhouette.c) with frame coherence "
      "(last frame's list retested, chains followed around both ends of each edge found, then random seeds from the "
      "sharpest-first edge order, a tenth of the budget) at each budget of edge tests, against `mc_sil_exact` (every "
      "face's facing, every edge). Recall: the screen length of the silhouette edges found over the exact set's, per "
      "frame after the first 10 (median, 5th percentile, minimum). Instructions: callgrind, the function alone, per "
      "frame. Both with a vertex cache (`mc_sil_cache`: each vertex met projected once a call); the row \"exact scan, "
      "no vertex cache\" projects each face's three corners for its facing, as both did before the cache. The last row "
      "of each mesh is the exact set as the lines style finds it every frame (`sil_check ... lines`: "
      "`mc_mesh_lines_sparse` drawing nothing, `MC_LINES_NO_HIDING` and no edge kind: the projection of every vertex "
      "into the lines style's vertex cache, every face's facing bit from it, the edge pass over the front faces; its "
      "count of silhouettes checked equal to the exact set's in every frame): what the search has to beat in a "
      "drawing.\n")
print("| mesh | faces | budget (tests) | tests per frame | facings per frame | recall median | p5 | min | Ir per frame | of the exact scan's |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
pts = {}
for m in dict.fromkeys(r[0] for r in rows):
    ex = parse(m, "exact")
    for b in [r[1] for r in rows if r[0] == m]:
        r = parse(m, b)
        frac = r["ir"] / ex["ir"]
        label = {"exact": "exact scan", "plain": "exact scan, no vertex cache",
                 "lines": "exact, the lines style's passes"}.get(b) or f"{int(b):,}"
        tests = "every front face" if b == "lines" else f"{r['tests']:,.0f}"
        print(f"| {m} | {r['faces']:,} | {label} | {tests} | {r['facings']:,.0f} | {r['median']:.3f} | "
              f"{r['p5']:.3f} | {r['min']:.3f} | {r['ir'] / 1e6:.2f} M | {100 * frac:.1f} % |")
        if b not in ("exact", "plain", "lines"): pts.setdefault(m, []).append((frac, r["median"], r["min"]))
print(f"\nLoad average at the end: {load}.")
with open(f"{out}/plot.dat", "w") as f:
    for m, p in pts.items():
        f.write(f"# {m}\n")
        for a in sorted(p): f.write(f"{100 * a[0]:.3f} {a[1]:.4f} {a[2]:.4f}\n")
        f.write("\n\n")
with open(f"{out}/plot.gp", "w") as f:
    f.write(f'set terminal pngcairo size 640,400\nset output "tests/bench/silhouette.png"\n'
            'set xlabel "instructions per frame, % of the exact scan"\nset ylabel "silhouette length found"\n'
            'set key bottom right\nset grid\nset yrange [0:1.02]\n')
    f.write("plot " + ", ".join(
        f'"{out}/plot.dat" index {i} using 1:2 with linespoints title "{m} median", '
        f'"{out}/plot.dat" index {i} using 1:3 with points title "{m} min"' for i, m in enumerate(pts)) + "\n")
PY
gnuplot "$out/plot.gp"
printf '\n%s\n' "![recall against instructions](silhouette.png)" >>"$out/section.md"
write_section "$results" silhouette "$out/section.md" "${cmds[@]}"
