#!/usr/bin/env bash
# Run time against error for the progressive mesh's level of detail. For each mesh (baked by modelc
# --as both, depth 5) tests/bench/lod_error.c draws the shaded style (mc_front_mesh_frame,
# MC_FRONT_SHADED: flat-shaded faces, back faces culled on a closed part, the vertex cache on) at a
# sequence of levels (face budgets as percentages of the full mesh's faces, mc_pmesh_lod_fit) over
# the views of a turn, and compares every frame with the full level's frame of the same view: PSNR of
# the RGB images (white background) and the fraction of pixels whose coverage differs; time per frame
# (all levels in one process, interleaved, rounds alternating the order) and callgrind instructions
# per frame (mc_front_mesh_frame only, with and without the vertex cache). Writes a marked section of
# RESULTS.md, tests/bench/lod_error.png (error against instructions: the Pareto fronts) and
# tests/bench/lod_strip.png (one view at a few levels side by side, a row per mesh).
#   tests/bench/lod_error.sh [RESULTS.md]
#   LOD_MODELS ("bunny00 fandisk"), LOD_PERCENTS ("1 2 5 10 20 50 100"), LOD_VIEWS (12), LOD_SIZE
#   (320x240), LOD_REPS (20: timed rounds of every level's views), LOD_PITCH (228, angle units of
#   4096 a turn: 20 degrees, as silhouette.sh), LOD_STRIP_VIEW (1: the strip's view, 0 .. LOD_VIEWS-1),
#   LOD_STRIP_PERCENTS ("1 2 5 20 100")
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/lib.sh   # runtime_snapshot, model_file
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
models=${LOD_MODELS:-bunny00 fandisk} percents=${LOD_PERCENTS:-1 2 5 10 20 50 100} views=${LOD_VIEWS:-12}
size=${LOD_SIZE:-320x240} reps=${LOD_REPS:-20} pitch=${LOD_PITCH:-228} strip_view=${LOD_STRIP_VIEW:-1}
strip_percents=${LOD_STRIP_PERCENTS:-1 2 5 20 100}
out=build/bench/lod_error
modelc=build/bin/modelc
[ -x "$modelc" ] || { echo "lod_error.sh: $modelc missing: run make gen" >&2; exit 1; }
command -v gnuplot >/dev/null || { echo "lod_error.sh: gnuplot missing: run make deps" >&2; exit 1; }
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
run_glob() { cmds+=("$1"); eval "$1"; }
plist=$(echo $percents | tr ' ' ',')
slist=$(echo $strip_percents | tr ' ' ',')

# the runtime, copied once so that every binary is built from the same sources
runtime_snapshot "$out/src" >/dev/null || { echo "lod_error.sh: cannot copy the runtime" >&2; exit 1; }
rt=$out/src/runtime
# with every runtime header (an inline function or a layout there changes the code as a .c file does)
rt_sha=$(cat "$rt"/src/{mesh_render,raster,xform_vertex,pmesh}.c "$rt"/front/common/mesh_frame.c \
    $(ls "$rt"/include/modelc/*.h "$rt"/src/*.h | sort) | sha256sum | cut -c1-12)
flags=(-O2 -g -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra "-I$rt/include" "-I$rt/front/host" "-I$rt/front/common")

: >"$out/rows.txt"
for m in $models; do
    src=$(model_file "$m") || { echo "lod_error.sh: $m: no such catalogue model, or it cannot be extracted" >&2; exit 1; }
    rm -rf "${out:?}/$m"
    run "$modelc" "$src" -o "$out" --name "$m" --depth 5 --as both -q
    run_glob "gcc ${flags[*]} -DPM=mc_pmesh_$m -include $out/$m/$m.h -o $out/$m-lod tests/bench/lod_error.c \
$rt/src/*.c $rt/front/common/mesh_frame.c $out/$m/*.c -lm"
    run "$out/$m-lod" --percent "$plist" --views "$views" --size "$size" --reps "$reps" --pitch "$pitch" \
        >"$out/$m.txt"
    for p in $percents; do
        run valgrind --tool=callgrind --toggle-collect=mc_front_mesh_frame --callgrind-out-file="$out/$m.$p.cg" \
            "$out/$m-lod" --cg "$p" --views "$views" --size "$size" --pitch "$pitch" >"$out/$m.$p.cg.txt" 2>"$out/$m.$p.cg.log"
        run valgrind --tool=callgrind --toggle-collect=mc_front_mesh_frame --callgrind-out-file="$out/$m.$p.nc.cg" \
            "$out/$m-lod" --cg "$p" --views "$views" --size "$size" --pitch "$pitch" --no-cache \
            >"$out/$m.$p.nc.cg.txt" 2>"$out/$m.$p.nc.cg.log"
    done
    run "$out/$m-lod" --ppm "$out/$m.strip" --view "$strip_view" --percent "$slist" --views "$views" --size "$size" \
        --pitch "$pitch" >"$out/$m.strip.txt"
    echo "$m" >>"$out/rows.txt"
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
cc_version=$(gcc --version | head -n1)
python3 - "$out" "$views" "$size" "$reps" "$pitch" "$strip_view" "$load" "$cc_version" "$rt_sha" "$percents" \
    "$strip_percents" >"$out/section.md" <<'PY'
import math, re, struct, sys, zlib
out, views, size, reps, pitch, strip_view, load, cc, rt_sha, percents, strip_percents = sys.argv[1:12]
views, strip_view = int(views), int(strip_view)
percents, strip_percents = percents.split(), strip_percents.split()
models = open(f"{out}/rows.txt").read().split()

def ir(path):
    return int(re.search(r"refs:\s+([\d,]+)", open(path).read()).group(1).replace(",", ""))

def levels(m):
    rows = {}
    for l in open(f"{out}/{m}.txt"):
        if not l.startswith("level "):
            continue
        f = l.split()
        d = dict(zip(f[0::2], f[1::2]))
        rows[d["level"]] = {k: float(v) for k, v in d.items()}
    return rows

deg = f"{int(pitch) * 360 / 4096:.1f}".rstrip("0").rstrip(".")
closed = ", ".join(f"{m} " + ("closed" if re.search(r" closed 1 ", open(f"{out}/{m}.txt").read()) else "open")
                   for m in models)
print("## Level of detail: run time against error\n")
print(f"`tests/bench/lod_error.sh`: each mesh baked by `modelc --as both` (depth 5) and drawn in the shaded style by "
      "tests/bench/lod_error.c: per frame `mc_front_mesh_frame(..., MC_FRONT_SHADED, ...)` (runtime/front/common/"
      f"mesh_frame.c: `mc_clear`, then `mc_mesh_render`'s flat-shaded faces, back faces culled when the part is closed: {closed}), "
      "the static vertex cache on. Levels: the finest with at most P % of the full mesh's faces (`mc_pmesh_lod_fit`). "
      f"Views: {views} of a turn of yaw, pitch {deg} degrees, zoom 1, orthographic, {size}. Each frame is compared with the "
      "full level's frame of the same view: PSNR of the RGB images (the palette's greys on a white background; MSE "
      f"pooled over the {views} views' pixels and channels; worst: the lowest of a single view) and the coverage "
      "difference (pixels covered in one frame and not the other, as a share of those covered in either, pooled; worst "
      f"view). Time: all levels in one process, {reps} rounds of every level's {views} frames (the order of the levels "
      "reversed every other round), wall-clock ms per frame, median over the frames; CPU the process's CPU time likewise. "
      "Instructions: callgrind, `mc_front_mesh_frame` only (clear and faces, with everything they call; setting the "
      f"level is outside it), per frame over the {views} views, with the vertex cache and without it (each face projects "
      f"its corners). gcc -O2 ({cc}); runtime from the working tree, copied to {out}/src/runtime (mesh_render.c, "
      f"raster.c, xform_vertex.c, pmesh.c, mesh_frame.c and the runtime's headers: sha256 {rt_sha}).\n")
print("| mesh | level | faces | vertices | PSNR dB | worst view | coverage difference | worst view | ms per frame | "
      "CPU ms | Ir per frame | of the full level's | Ir without the cache |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
pts = {}
for m in models:
    rows = levels(m)
    full = ir(f"{out}/{m}.100.cg.log") / views if "100" in rows else None
    for p in percents:
        r = rows[p]
        i = ir(f"{out}/{m}.{p}.cg.log") / views
        nc = ir(f"{out}/{m}.{p}.nc.cg.log") / views
        psnr = "exact" if math.isinf(r["psnr"]) else f"{r['psnr']:.2f}"
        worst = "exact" if math.isinf(r["psnr_min"]) else f"{r['psnr_min']:.2f}"
        share = f"{100 * i / full:.1f} %" if full else "-"
        print(f"| {m} | {p} % | {r['faces']:,.0f} | {r['vertices']:,.0f} | {psnr} | {worst} | "
              f"{100 * r['cov_diff']:.3f} % | {100 * r['cov_diff_max']:.3f} % | {r['ms']:.3f} | {r['cpu_ms']:.3f} | "
              f"{i / 1e6:.2f} M | {share} | {nc / 1e6:.2f} M |")
        pts.setdefault(m, []).append((i, r["psnr"], r["cov_diff"], r["psnr_min"], r["cov_diff_max"], p, r["ms"]))
print(f"\nLoad average at the end: {load}.")

with open(f"{out}/plot.dat", "w") as f:
    for m, p in pts.items():
        f.write(f"# {m}: Ir per frame (M), PSNR, worst view PSNR, coverage difference %, worst view %, level %\n")
        for a in sorted(p):
            if math.isinf(a[1]):
                continue   # the full level: no error
            f.write(f"{a[0] / 1e6:.4f} {a[1]:.4f} {a[3]:.4f} {100 * a[2]:.5f} {100 * a[4]:.5f} {a[5]}\n")
        f.write("\n\n")
with open(f"{out}/plot.gp", "w") as f:
    f.write('set terminal pngcairo size 960,460\nset output "tests/bench/lod_error.png"\n'
            'set multiplot layout 1,2 title "shaded frames against the full level: error against instructions per frame"\n'
            'set logscale x\nset grid\nset xlabel "instructions per frame (M, mc\\\\_front\\\\_mesh\\\\_frame)"\n'
            'set key outside below horizontal maxcols 2 font ",9"\nset offsets graph 0.08, graph 0.08, graph 0.1, graph 0.05\n'
            'set ylabel "PSNR (dB; higher is better)"\n')
    f.write("plot " + ", ".join(
        f'"{out}/plot.dat" index {k} using 1:2 with linespoints pt 7 title "{m} (pooled)", '
        f'"{out}/plot.dat" index {k} using 1:3 with points pt 6 title "{m} (worst view)", '
        f'"{out}/plot.dat" index {k} using 1:2:6 with labels offset 0,1 font ",8" notitle' for k, m in enumerate(pts)) + "\n")
    f.write('set logscale y\nset offsets graph 0.08, graph 0.08, 0, 0\nset ylabel "coverage difference (%; lower is better)"\n')
    f.write("plot " + ", ".join(
        f'"{out}/plot.dat" index {k} using 1:4 with linespoints pt 7 title "{m} (pooled)", '
        f'"{out}/plot.dat" index {k} using 1:5 with points pt 6 title "{m} (worst view)", '
        f'"{out}/plot.dat" index {k} using 1:4:6 with labels offset 0,1 font ",8" notitle' for k, m in enumerate(pts)) + "\n")
    f.write("unset multiplot\n")

# ---- the strip: view strip_view at the strip's levels, a row per mesh, the level's % in the corner ----
FONT = {"0": "111101101101111", "1": "010110010010111", "2": "111001111100111", "3": "111001111001111",
        "4": "101101111001001", "5": "111100111001111", "6": "111100111101111", "7": "111001001001001",
        "8": "111101111101111", "9": "111101111001111", ".": "000000000000010", "%": "101001010100101"}

def netpbm(path):
    data = open(path, "rb").read()
    magic, dims, maxval, px = data.split(b"\n", 3)
    w, h = map(int, dims.split())
    return w, h, px

def png(path, w, h, rgb):
    raw = b"".join(b"\0" + rgb[3 * w * y:3 * w * (y + 1)] for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))

tiles = [[netpbm(f"{out}/{m}.strip.{p}.ppm") for p in strip_percents] for m in models]
tw, th = tiles[0][0][0], tiles[0][0][1]
gap, scale = 4, 2
W, H = len(strip_percents) * tw + (len(strip_percents) - 1) * gap, len(models) * th + (len(models) - 1) * gap
img = bytearray([160]) * (3 * W * H)
for r, row in enumerate(tiles):
    for c, (w, h, px) in enumerate(row):
        x0, y0 = c * (tw + gap), r * (th + gap)
        for y in range(h):
            o = 3 * ((y0 + y) * W + x0)
            img[o:o + 3 * w] = px[3 * w * y:3 * w * (y + 1)]
        for k, ch in enumerate(strip_percents[c] + "%"):   # the label, top left
            for gy in range(5):
                for gx in range(3):
                    if FONT[ch][3 * gy + gx] == "1":
                        for sy in range(scale):
                            for sx in range(scale):
                                o = 3 * ((y0 + 4 + gy * scale + sy) * W + x0 + 4 + k * 4 * scale + gx * scale + sx)
                                img[o:o + 3] = b"\x00\x00\x00"
png("tests/bench/lod_strip.png", W, H, bytes(img))
strip_faces = {m: re.findall(r"faces (\d+)", open(f"{out}/{m}.strip.txt").read()) for m in models}
print("\n![error against instructions per frame](lod_error.png)\n")
print("`tests/bench/lod_error.png`: PSNR (left) and coverage difference (right) against instructions per frame, each "
      "point a level (labelled with its %; the full level, with no error, is left out).\n")
print("![levels of detail](lod_strip.png)\n")
print(f"`tests/bench/lod_strip.png`: view {strip_view} of the turn (yaw {strip_view * 360 / views:g} degrees) at "
      + ", ".join(f"{p} %" for p in strip_percents) + " of the faces, left to right; rows: "
      + "; ".join(f"{m} ({', '.join(f'{int(n):,}' for n in strip_faces[m])} faces)" for m in models) + ".")
PY
gnuplot "$out/plot.gp"
write_section "$results" lod-error "$out/section.md" "${cmds[@]}"
