#!/usr/bin/env bash
# Filled triangles side by side with Mesa in one run: each mesh baked by modelc --as both and drawn at
# its full level of detail, flat-shaded, by modelc's mc_mesh_render (tests/bench/mesh_frames.c) and by
# Mesa's llvmpipe on one thread through OSMesa (tests/bench/osmesa_mesh.c: the same triangles in the
# same palette colours, uploaded once into a vertex buffer, the same orthographic view, depth test on
# a 16-bit buffer); the frontal frame's coverage masks compared; per round, a full turn timed by each,
# alternately; callgrind instructions of mc_mesh_render per frame and per face. Then line drawings
# (silhouettes, creases, borders, hidden lines removed) the same way: modelc's mc_front_mesh_frame in
# the lines style (mesh_frames --style lines) against Mesa "the GPU way" (osmesa_mesh --style lines: a
# depth pre-pass of the faces with polygon offset, then GL_LINES of the same edges, listed from the
# runtime before the timing), a second table; the frontal drawings' line pixels compared and shown
# side by side in tests/bench/lines_NAME.png. Appends (replacing an earlier copy) a marked section to
# RESULTS.md.
#   tests/bench/mesh.sh [RESULTS.md]
#   MESH_MODELS ("bunny00 fandisk lion_head"), MESH_ROUNDS (7), MESH_FRAMES (100), MESH_SIZE (320x240),
#   MESH_CG_FRAMES (20: frames of the turn under callgrind), MESH_LINES_MODELS (MESH_MODELS: the line
#   drawings' table), MESH_LINES_PICTURE (bunny00: the model of tests/bench/lines_NAME.png, if drawn),
#   MESH_RUNTIME_REV (empty: the working tree's runtime/; else a git revision to take runtime/ from,
#   e.g. HEAD, for when the working tree's runtime does not match build/bin/modelc's output),
#   MESH_GROUPS (32: the bakes' --mesh-groups, the face groups the line drawings' face pass passes
#   over; 0: none)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/lib.sh   # runtime_snapshot, model_file
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
models=${MESH_MODELS:-bunny00 fandisk lion_head} rounds=${MESH_ROUNDS:-7} frames=${MESH_FRAMES:-100}
size=${MESH_SIZE:-320x240} cg_frames=${MESH_CG_FRAMES:-20} rev=${MESH_RUNTIME_REV:-}
lines_models=${MESH_LINES_MODELS:-$models} lines_picture=${MESH_LINES_PICTURE:-bunny00} groups=${MESH_GROUPS:-32}
out=build/bench/mesh
modelc=build/bin/modelc
[ -x "$modelc" ] || { echo "mesh.sh: $modelc missing: run make gen" >&2; exit 1; }
[ -f /usr/include/GL/osmesa.h ] || { echo "mesh.sh: GL/osmesa.h missing: run make deps (libosmesa6-dev)" >&2; exit 1; }
mkdir -p "$out"
rm -f "$out/FAILED"
cmds=()
run() { cmds+=("$*"); "$@"; }
# a command with globs, logged as written (not expanded) and then run
run_glob() { cmds+=("$1"); eval "$1"; }

# the runtime, copied once so that every binary is built from the same sources
runtime_from=$(runtime_snapshot "$out/src" "$rev") || { echo "mesh.sh: cannot copy the runtime" >&2; exit 1; }
rt=$out/src/runtime
# the sources each table measures, with every runtime header (an inline function or a layout there
# changes the code as much as one in a .c file)
headers=$(ls "$rt"/include/modelc/*.h "$rt"/src/*.h | sort)
rt_sha=$(cat "$rt"/src/{mesh_render,raster,xform_vertex,pmesh}.c $headers | sha256sum | cut -c1-12)
lines_sha=$(cat "$rt"/src/{mesh_lines,mesh_creases,line,sdepth,raster,mesh_render,xform_vertex,pmesh}.c "$rt"/front/common/mesh_frame.c $headers |
    sha256sum | cut -c1-12)
flags=(-O2 -g -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra "-I$rt/include" "-I$rt/front/host" "-I$rt/front/common")

# timed_rounds M STEM [ARGS...]: rounds of the timed turn, modelc's and Mesa's alternately and the
# order swapped every round, both with ARGS; their outputs in STEM.rR.modelc.txt and STEM.rR.mesa.txt,
# and a line a round in STEM.times: modelc's and Mesa's median wall ms, then Mesa's and modelc's CPU ms
timed_rounds() {
    local m=$1 stem=$2 r side a b c d
    shift 2
    : >"$stem.times"
    for r in $(seq 1 "$rounds"); do
        for side in $( [ $((r % 2)) = 1 ] && echo "modelc mesa" || echo "mesa modelc"); do
            if [ "$side" = modelc ]; then
                "$out/$m-frames" "$@" --time "$frames" --size "$size" >"$stem.r$r.modelc.txt"
            else
                env LP_NUM_THREADS=0 "$out/$m-osmesa" "$@" --time "$frames" --size "$size" >"$stem.r$r.mesa.txt"
            fi
        done
        a=$(sed -n 's/^ms per frame (median) //p' "$stem.r$r.modelc.txt")
        b=$(sed -n 's/^ms per frame (median) //p' "$stem.r$r.mesa.txt")
        c=$(sed -n 's/^cpu ms per frame (median) //p' "$stem.r$r.mesa.txt")
        d=$(sed -n 's/^cpu ms per frame (median) //p' "$stem.r$r.modelc.txt")
        echo "$a $b $c $d" >>"$stem.times"
    done
}

: >"$out/rows.txt"
for m in $models; do
    # the catalogue's file (lion_head is lion-head.off)
    src=$(model_file "$m") || { echo "mesh.sh: $m: no such catalogue model, or it cannot be extracted" >&2; exit 1; }
    rm -rf "${out:?}/$m"
    run "$modelc" "$src" -o "$out" --name "$m" --depth 5 --as both --mesh-groups "$groups" -q
    run_glob "gcc ${flags[*]} -DPM=mc_pmesh_$m -include $out/$m/$m.h -o $out/$m-frames \
tests/bench/mesh_frames.c $rt/src/*.c $rt/front/common/mesh_frame.c $out/$m/*.c" ||
        { echo "mesh.sh: the bake does not build against the runtime from $runtime_from: is $modelc older" \
               "than runtime/ (make gen), or set MESH_RUNTIME_REV=HEAD" >&2; exit 1; }
    run_glob "gcc ${flags[*]} -DPM=mc_pmesh_$m -include $out/$m/$m.h -ffunction-sections -fdata-sections \
-o $out/$m-osmesa tests/bench/osmesa_mesh.c $rt/src/*.c $out/$m/*.c -Wl,--gc-sections -lOSMesa -lm"
    # the frontal frame: images and coverage masks of both
    run "$out/$m-frames" --size "$size" --yaw 0 --ppm "$out/$m.modelc.ppm" --mask "$out/$m.modelc.pgm" >"$out/$m.img.txt"
    run env LP_NUM_THREADS=0 "$out/$m-osmesa" --size "$size" --yaw 0 --ppm "$out/$m.mesa.ppm" \
        --mask "$out/$m.mesa.pgm" >"$out/$m.mesa.img.txt"
    run valgrind --tool=callgrind --toggle-collect=mc_mesh_render --callgrind-out-file="$out/$m.cg" \
        "$out/$m-frames" --frames "$cg_frames" --size "$size" >"$out/$m.cg.txt" 2>"$out/$m.cg.log"
    timed_rounds "$m" "$out/$m"
    echo "$m" >>"$out/rows.txt"
done
cmds+=("$out/NAME-frames --time $frames --size $size; env LP_NUM_THREADS=0 $out/NAME-osmesa --time $frames --size $size   # per round, alternately, $rounds rounds")

# line drawings: the same binaries, --style lines
: >"$out/lines_rows.txt"
for m in $lines_models; do
    [ -x "$out/$m-frames" ] || { echo "mesh.sh: $m of MESH_LINES_MODELS is not in MESH_MODELS" >&2; exit 1; }
    run "$out/$m-frames" --style lines --size "$size" --yaw 0 --ppm "$out/$m.lines.modelc.ppm" \
        --mask "$out/$m.lines.modelc.pgm" >"$out/$m.lines.img.txt"
    run env LP_NUM_THREADS=0 "$out/$m-osmesa" --style lines --size "$size" --yaw 0 --ppm "$out/$m.lines.mesa.ppm" \
        --mask "$out/$m.lines.mesa.pgm" >"$out/$m.lines.mesa.img.txt"
    run valgrind --tool=callgrind --toggle-collect=mc_front_mesh_frame --callgrind-out-file="$out/$m.lines.cg" \
        "$out/$m-frames" --style lines --frames "$cg_frames" --size "$size" >"$out/$m.lines.cg.txt" 2>"$out/$m.lines.cg.log"
    # each pass's instructions, with what it calls (the breakdown table)
    run_glob "callgrind_annotate --inclusive=yes --threshold=100 $out/$m.lines.cg >$out/$m.lines.cg.incl.txt 2>/dev/null"
    timed_rounds "$m" "$out/$m.lines" --style lines
    echo "$m" >>"$out/lines_rows.txt"
done
cmds+=("$out/NAME-frames --style lines --time $frames --size $size; env LP_NUM_THREADS=0 $out/NAME-osmesa --style lines --time $frames --size $size   # per round, alternately, $rounds rounds")
load=$(cut -d' ' -f1-3 /proc/loadavg)
renderer=$(sed -n 's/^renderer: //p' "$out/$(echo $models | cut -d' ' -f1).mesa.img.txt")
version=$(sed -n 's/^version: //p' "$out/$(echo $models | cut -d' ' -f1).mesa.img.txt")
cc_version=$(gcc --version | head -n1)
BAKE_GROUPS=$groups python3 - "$out" "$rounds" "$frames" "$size" "$cg_frames" "$load" "$renderer" "$version" "$cc_version" \
    "$runtime_from" "$rt_sha" "$lines_sha" "$lines_picture" >"$out/section.md" <<'PY'
import os, re, statistics, struct, sys, zlib
out, rounds, frames, size, cg_frames, load, renderer, version, cc, rt_from, rt_sha, lines_sha, picture = sys.argv[1:14]
cg_frames = int(cg_frames)

def netpbm(path):
    data = open(path, "rb").read()
    magic, dims, maxval, pixels = data.split(b"\n", 3)
    w, h = map(int, dims.split())
    return w, h, pixels

def field(path, key):
    return float(re.search(r"^" + re.escape(key) + r" ([\d.]+)$", open(path).read(), re.M).group(1))

print("## Filled triangles: mc_mesh_render against Mesa llvmpipe\n")
print("`tests/bench/mesh.sh`: each mesh baked by `modelc --as both` and drawn at its full level of detail, "
      "flat-shaded, by modelc's `mc_mesh_render` (tests/bench/mesh_frames.c: `mc_clear` + `mc_mesh_render` per frame) "
      f"and by Mesa's software OpenGL through OSMesa ({renderer}, {version}, `LP_NUM_THREADS=0`: one thread; "
      "tests/bench/osmesa_mesh.c: the same triangles, three unshared vertices each with the palette colour "
      "`mc_mesh_shade` gives the face, uploaded once into a vertex buffer; `glClear` + `glDrawArrays(GL_TRIANGLES)` + "
      "`glFinish` per frame, depth test `GL_LESS` on a 16-bit depth buffer, no culling). The same view: orthographic, "
      f"zoom 1, a full turn of yaw in {frames} frames at {size}. Per round, each side times the turn once, alternately "
      f"(the order swapped every round), {rounds} rounds: wall-clock ms per frame, median over the frames of a run and "
      "then over rounds; Mesa's process CPU time likewise; ratio = median over rounds of Mesa's wall ms / modelc's in "
      f"the same round. gcc -O2 ({cc}); runtime from {rt_from}, copied to {out}/src/runtime (mesh_render.c, raster.c, xform_vertex.c, pmesh.c and "
      f"the runtime's headers: sha256 {rt_sha}). Instructions: callgrind, `mc_mesh_render` only (with everything it calls), a turn of "
      f"{cg_frames} frames; per face = per frame / faces of the level (every face, drawn or not). Pixels per frame: "
      "the pixels modelc's drawn faces cover before the depth test (`mc_mesh_stats.pixels`, mean over the turn). "
      "Coverage difference: the frontal frame's pixels covered by one renderer and not the other, as a share of those "
      "covered by either (edge pixels: modelc projects to 1/16 pixel, llvmpipe to 1/256).\n")
print("| mesh | faces | pixels per frame | modelc ms | Mesa wall ms | Mesa CPU ms | ratio | modelc Ir per frame | "
      "Ir per face | coverage difference |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
per_round, colours, bad = [], [], []
for m in open(f"{out}/rows.txt").read().split():
    rows = [list(map(float, l.split())) for l in open(f"{out}/{m}.times")]
    a = statistics.median(r[0] for r in rows)
    b = statistics.median(r[1] for r in rows)
    c = statistics.median(r[2] for r in rows)
    ratio = statistics.median(r[1] / r[0] for r in rows)
    faces = int(field(f"{out}/{m}.r1.modelc.txt", "triangles per frame"))
    pixels = field(f"{out}/{m}.r1.modelc.txt", "pixels per frame")
    refs = int(re.search(r"refs:\s+([\d,]+)", open(f"{out}/{m}.cg.log").read()).group(1).replace(",", ""))
    cg_faces = field(f"{out}/{m}.cg.txt", "faces per frame")
    ir_frame = refs / cg_frames
    w, h, ma = netpbm(f"{out}/{m}.modelc.pgm")
    w2, h2, mb = netpbm(f"{out}/{m}.mesa.pgm")
    assert (w, h) == (w2, h2)
    n = w * h
    either = sum(1 for i in range(n) if ma[i] or mb[i])
    only_a = sum(1 for i in range(n) if ma[i] and not mb[i])
    only_b = sum(1 for i in range(n) if mb[i] and not ma[i])
    diff = (only_a + only_b) / max(either, 1)
    if diff > 0.01:
        bad.append(m)
    _, _, ca = netpbm(f"{out}/{m}.modelc.ppm")
    _, _, cb = netpbm(f"{out}/{m}.mesa.ppm")
    both = [i for i in range(n) if ma[i] and mb[i]]
    cdiff = sum(1 for i in both if ca[3 * i:3 * i + 3] != cb[3 * i:3 * i + 3])
    colours.append(f"{m} {cdiff} of {len(both):,} ({100 * cdiff / max(len(both), 1):.2f} %)")
    print(f"| {m} | {faces:,} | {pixels:,.0f} | {a:.2f} | {b:.2f} | {c:.2f} | {ratio:.2f}x | {ir_frame / 1e6:.2f} M | "
          f"{ir_frame / cg_faces:.0f} | {only_a + only_b} px of {either:,} ({100 * diff:.2f} %) |")
    per_round.append(f"{m}: " + ", ".join(f"{r[0]:.2f} / {r[1]:.2f} / {r[2]:.2f}" for r in rows))
print()
print("Per round (modelc wall / Mesa wall / Mesa CPU ms per frame): " + "; ".join(per_round) + ".")
print()
print("Frontal frame, pixels both cover whose colour differs (a different face wins a pixel near an edge or where "
      "depths tie): " + "; ".join(colours) + ".")

# ---- line drawings --------------------------------------------------------------------------------
def png(path, w, h, rgb):
    raw = b"".join(b"\0" + rgb[3 * w * y:3 * w * (y + 1)] for y in range(h))
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    open(path, "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))

lines_rows = open(f"{out}/lines_rows.txt").read().split()

def inclusive(m, name):
    """Instructions of function `name` with everything it calls, in the lines callgrind run (0: not called):
    the largest of its entries (a function with inlined code from headers has one entry per file, the
    function's own file holding the calls into it)."""
    text = open(f"{out}/{m}.lines.cg.incl.txt").read()
    hits = re.findall(r"^\s*([\d,]+) \([^)]*\)\s+\S+:" + re.escape(name) + r"(?: \[.*)?$", text, re.M)
    return max((int(h.replace(",", "")) for h in hits), default=0)

def breakdown_section(rows):
    """Where a line drawing's instructions go, pass by pass, and what the frame would be without the two
    passes over every front face (the edge kinds, the boxes): the bound those passes set on the ratio."""
    lines = ["### Where a line drawing's instructions go\n",
             "The callgrind runs above, per frame, each pass with what it calls (`callgrind_annotate --inclusive=yes --threshold=100`): "
             "projection `mc_mesh_project` (every vertex of the level into the cache); facing `set_facing` (every face's "
             "bit); lines `draw_edge` (each line's ends, depth offset and pixels offered to the buffer); face pass "
             "`face_pass`, split into the faces whose box meets a line pixel (`mc_raster_triangle_hide_box`, and "
             "`hide_clipped` for a face with a flagged corner) and the boxes of all the others; buffer "
             "`mc_sdepth_init` (the target made paper); the edge pass is what is left of `mc_mesh_lines_sparse` (each "
             "face's edge kinds: the neighbours' facing bits, the crease bits). Without the edge pass and the boxes "
             "(were they free), the frame would take the rest; the last two columns estimate it at the frame's own "
             "instructions a millisecond (modelc ms above / its instructions) and set it against Mesa's ms above.\n",
             "| mesh | frame | projection | facing | edge pass | lines | face pass: boxes | face pass: faces meeting a "
             "line pixel | buffer | rest, without the edge pass and the boxes | its ms at the frame's rate | "
             "ratio to Mesa at that |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for m in rows:
        tr = [list(map(float, l.split())) for l in open(f"{out}/{m}.lines.times")]
        ms, mesa = statistics.median(r[0] for r in tr), statistics.median(r[1] for r in tr)
        c = {k: inclusive(m, k) / cg_frames for k in ("mc_front_mesh_frame", "mc_mesh_lines_sparse", "mc_mesh_project",
             "set_facing", "face_pass", "mc_raster_triangle_hide_box", "hide_clipped", "draw_edge", "mc_sdepth_init",
             "mc_mesh_creases_update")}
        frame = c["mc_front_mesh_frame"]
        tri = c["mc_raster_triangle_hide_box"] + c["hide_clipped"]
        boxes = c["face_pass"] - tri
        edges = (c["mc_mesh_lines_sparse"] - c["mc_mesh_project"] - c["set_facing"] - c["face_pass"] - c["draw_edge"]
                 - c["mc_mesh_creases_update"])
        rest = frame - edges - boxes
        rest_ms = ms * rest / frame
        M = lambda v: f"{v / 1e6:.2f} M"
        lines.append(f"| {m} | {M(frame)} | {M(c['mc_mesh_project'])} | {M(c['set_facing'])} | {M(edges)} | "
                     f"{M(c['draw_edge'])} | {M(boxes)} | {M(tri)} | {M(c['mc_sdepth_init'])} | {M(rest)} | "
                     f"{rest_ms:.2f} | {mesa / rest_ms:.2f}x |")
    return "\n".join(lines)
if lines_rows:
    closed = ", ".join(f"{m} " + ("closed" if re.search(r"closed 1", open(f"{out}/{m}.lines.r1.modelc.txt").read())
                                  else "open") for m in lines_rows)
    print("\n## Line drawings: mc_front_mesh_frame (lines) against Mesa llvmpipe's depth pre-pass + GL_LINES\n")
    print(f"The same bakes, binaries and view, the line-drawing style: silhouettes, creases and borders with hidden lines "
          "removed. modelc: `mesh_frames --style lines`, per frame `mc_front_mesh_frame(..., MC_FRONT_LINES, ...)` "
          "(runtime/front/common/mesh_frame.c with the sparse depth buffer: the target made paper, then "
          "`mc_mesh_lines_sparse` finds every face's facing and every edge's kind, offers the silhouettes', creases' and "
          "borders' pixels, less a per-edge depth offset, to the buffer (`mc_line_sdepth`), then passes the faces, back "
          f"faces culled when the part is closed ({closed}), each emptying the line pixels it hides "
          "(`mc_raster_triangle_hide`: only a face whose box holds a line pixel at or beyond its least depth is set up; "
          f"the bakes' faces in groups of {os.environ['BAKE_GROUPS']} (`--mesh-groups`, pmesh.h; 0: none), a group whose "
          "projected box holds no line pixel at or beyond its least depth passed over whole), the vertex cache on, "
          "mc_mesh_lines' memory (`MC_MESH_LINES_BYTES(faces)`) and the buffer's bits static; an untimed frame first "
          "computes the level's crease bits, which "
          "mc_mesh_lines keeps while the level is unchanged. Mesa \"the GPU way\": `osmesa_mesh --style lines`: for each "
          "frame of the turn, the edges modelc draws in it are listed before the timing from the runtime, exactly as "
          "mc_mesh_lines enumerates them (`mc_mesh_facing` for the frame's view, each face's edges with the neighbour "
          "`mc_pmesh_lod_opposite` none or later, `mc_mesh_edge_kind`, silhouettes, creases and borders kept) and put "
          "with their colours into the vertex buffer after the faces (one upload); timed per frame: `glClear` + the depth "
          "pre-pass (`glDrawArrays(GL_TRIANGLES)` of all the faces in paper, `glPolygonOffset(1, 1)` on "
          "`GL_POLYGON_OFFSET_FILL`, back faces culled) + `glDrawArrays(GL_LINES)` of the frame's edges + `glFinish`, depth "
          "test `GL_LEQUAL`. So Mesa is not charged for finding the edges; \"edge list ms\" is what that listing took per "
          "frame on the CPU (wall clock, median, once per run). Both sides list the same number of lines over the turn "
          "(checked every round). Lines per frame: silhouettes + creases + borders (`mc_lines_stats`, mean over the turn); "
          "line pixels: the pixels of modelc's lines before the depth test (`mc_lines_stats.pixels`, mean). Rounds, medians "
          "and ratio as above (ratio: median over rounds of Mesa's wall ms / modelc's; CPU ratio likewise with both "
          "sides' process CPU time). Instructions: callgrind, `mc_front_mesh_frame` only (with everything it calls: "
          f"paper, lines, faces), a turn of {cg_frames} frames after the untimed one. mesh_lines.c, mesh_creases.c, line.c, sdepth.c, raster.c, "
          f"mesh_render.c, xform_vertex.c, pmesh.c, mesh_frame.c and the runtime's headers: sha256 {lines_sha}.\n")
    print("| mesh | lines per frame | silhouettes / creases / borders | line pixels | modelc ms | modelc CPU ms | "
          "Mesa wall ms | Mesa CPU ms | ratio | CPU ratio | edge list ms | modelc Ir per frame |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    per_round, cmp_lines = [], []
    for m in lines_rows:
        rows = [list(map(float, l.split())) for l in open(f"{out}/{m}.lines.times")]
        a = statistics.median(r[0] for r in rows)
        b = statistics.median(r[1] for r in rows)
        c = statistics.median(r[2] for r in rows)
        d = statistics.median(r[3] for r in rows)
        ratio = statistics.median(r[1] / r[0] for r in rows)
        cratio = statistics.median(r[2] / r[3] for r in rows)
        f1 = f"{out}/{m}.lines.r1.modelc.txt"
        nl, px = field(f1, "lines per frame"), field(f1, "line pixels per frame")
        sil, cre, bor = (field(f1, k + " per frame") for k in ("silhouettes", "creases", "borders"))
        for r in range(1, len(rows) + 1):
            ta = field(f"{out}/{m}.lines.r{r}.modelc.txt", "lines total")
            tb = field(f"{out}/{m}.lines.r{r}.mesa.txt", "lines total")
            if ta != tb:
                bad.append(f"{m} (lines listed: modelc {ta:.0f}, Mesa {tb:.0f})")
        lms = statistics.median(field(f"{out}/{m}.lines.r{r}.mesa.txt", "edge list ms per frame (median)")
                                for r in range(1, len(rows) + 1))
        refs = int(re.search(r"refs:\s+([\d,]+)", open(f"{out}/{m}.lines.cg.log").read()).group(1).replace(",", ""))
        print(f"| {m} | {nl:,.0f} | {sil:,.0f} / {cre:,.0f} / {bor:,.0f} | {px:,.0f} | {a:.2f} | {d:.2f} | {b:.2f} | "
              f"{c:.2f} | {ratio:.2f}x | {cratio:.2f}x | {lms:.2f} | {refs / cg_frames / 1e6:.2f} M |")
        per_round.append(f"{m}: " + ", ".join(f"{r[0]:.2f} / {r[3]:.2f} / {r[1]:.2f} / {r[2]:.2f}" for r in rows))
        # the frontal drawings: line pixels (modelc: a line colour; Mesa: alpha 255, a line drawn there)
        w, h, ma = netpbm(f"{out}/{m}.lines.modelc.pgm")
        w2, h2, mb = netpbm(f"{out}/{m}.lines.mesa.pgm")
        assert (w, h) == (w2, h2)
        n = w * h
        na, nb = sum(1 for i in range(n) if ma[i]), sum(1 for i in range(n) if mb[i])
        only_a = sum(1 for i in range(n) if ma[i] and not mb[i])
        only_b = sum(1 for i in range(n) if mb[i] and not ma[i])
        either = na + nb - (na - only_a)
        nlf = re.search(r"lines (\d+)", open(f"{out}/{m}.lines.img.txt").read()).group(1)
        cmp_lines.append(f"{m}: {int(nlf):,} lines, line pixels modelc {na:,}, Mesa {nb:,}; modelc's only {only_a:,}, "
                         f"Mesa's only {only_b:,}: {100 * (only_a + only_b) / max(either, 1):.1f} % of the {either:,} "
                         "pixels either draws")
        if m == picture:
            _, _, ca = netpbm(f"{out}/{m}.lines.modelc.ppm")
            _, _, cb = netpbm(f"{out}/{m}.lines.mesa.ppm")
            gap, W = 4, 3 * w + 2 * 4
            img = bytearray([160]) * (3 * W * h)
            for y in range(h):
                for x in range(w):
                    i = y * w + x
                    for k, (x0, src) in enumerate(((0, ca), (w + gap, cb))):
                        o = 3 * (y * W + x0 + x)
                        img[o:o + 3] = src[3 * i:3 * i + 3]
                    o = 3 * (y * W + 2 * (w + gap) + x)
                    img[o:o + 3] = (bytes((0, 0, 0)) if ma[i] and mb[i] else bytes((220, 0, 0)) if ma[i]
                                    else bytes((0, 70, 255)) if mb[i] else bytes((255, 255, 255)))
            png(f"tests/bench/lines_{m}.png", W, h, bytes(img))
    print()
    print("Per round (modelc wall / modelc CPU / Mesa wall / Mesa CPU ms per frame): " + "; ".join(per_round) + ".")
    print()
    print("Frontal drawings (yaw 0), the pixels holding a line: " + "; ".join(cmp_lines) + ". They differ by the "
          "rasterization rules, not by the edges (the same list): modelc's `mc_line` draws the Bresenham line between the pixels holding the projected endpoints (their 1/16-pixel positions "
          "truncated), both ends included, and hides a line pixel only where a face is nearer than it by more than a per-edge "
          "offset (2 depth units plus one pixel of the steeper depth slope of the edge's two faces); llvmpipe draws the "
          "diamond-exit line between the exact endpoints (the last pixel left out) against faces pushed back by "
          "`glPolygonOffset(1, 1)`. Where a line runs one pixel apart the two masks differ by twice its length; where a "
          "silhouette runs over faces seen nearly edge-on the offsets decide whether it shows.")
    if picture in lines_rows:
        print(f"\n![{picture}: modelc, Mesa, both](lines_{picture}.png)\n")
        print(f"`tests/bench/lines_{picture}.png`: the frontal drawing of {picture} by modelc (left) and by Mesa "
              "(middle); right, the line pixels of both (black), of modelc only (red) and of Mesa only (blue).\n")
    print("\n" + breakdown_section(lines_rows) + "\n")
print(f"Load average at the end: {load}.")
if bad:
    print(f"\n**Coverage masks differ by more than 1 %, or the line lists differ, for: {', '.join(bad)}.**")
    sys.stderr.write(f"mesh.sh: coverage masks differ by more than 1 % or line lists differ for {', '.join(bad)}\n")
    open(f"{out}/FAILED", "w").write(" ".join(bad) + "\n")
PY
write_section "$results" mesh "$out/section.md" "${cmds[@]}"
if [ -f "$out/FAILED" ]; then rm -f "$out/FAILED"; exit 1; fi
