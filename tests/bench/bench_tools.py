#!/usr/bin/env python3
"""Helpers for tests/bench/run.sh (standard library only).

  bench_tools.py cg-total FILE                     total Ir of a callgrind output file
  bench_tools.py ir-per-point CG.log FRAMES.txt    Ir per drawn point of a callgrind_frames run
  bench_tools.py cg-lines FILE SRCDIR N            top N source lines (self Ir) and functions, markdown
  bench_tools.py ply-check ORIG.ply DECODED.ply    are the decoded (draco_decoder) points the same cells?
  bench_tools.py image-cmp A.ppm B.ppm A.pgm B.pgm  compare two frames (colour) and their coverage masks
  bench_tools.py report RESULTS_DIR OUT.md         write the markdown report
"""
import json
import os
import re
import statistics
import struct
import sys


# ---- callgrind -----------------------------------------------------------------------------------

def cg_parse(path):
    """Self cost per (file, line) and per function from a callgrind file written with
    --compress-strings=no --compress-pos=no (positions: line, events: Ir)."""
    lines, funcs = {}, {}
    total = None
    events, totals = ["Ir"], {}
    fl = cur = fn = None
    skip_next = False
    with open(path) as f:
        for raw in f:
            s = raw.rstrip("\n")
            if not s or s.startswith("#"):
                continue
            if s.startswith("events:"):
                events = s.split(":", 1)[1].split()
                continue
            if s.startswith(("summary:", "totals:")):
                vals = [int(v) for v in s.split(":", 1)[1].split()]
                totals = dict(zip(events, vals))
                total = vals[0]
                continue
            m = re.match(r"^(\w+)=(.*)$", s)
            if m:
                k, v = m.groups()
                if k == "fl":
                    fl = cur = v
                elif k in ("fi", "fe"):
                    cur = v
                elif k == "fn":
                    fn, cur = v, fl
                elif k == "calls":
                    skip_next = True   # the next cost line is the call's inclusive cost
                continue
            if s[0].isdigit() or s[0] in "+-*":
                parts = s.split()
                if skip_next:
                    skip_next = False
                    continue
                if len(parts) < 2 or not parts[0].isdigit():
                    continue
                ln, ir = int(parts[0]), int(parts[1])
                lines[(cur, ln)] = lines.get((cur, ln), 0) + ir
                funcs[fn] = funcs.get(fn, 0) + ir
    cg_parse.totals = totals
    return total, lines, funcs


def cg_total(path):
    """Every event's total, one 'EVENT: N' line each (Ir first)."""
    cg_parse(path)
    for k, v in cg_parse.totals.items():
        print(f"{k}: {v}")


def ir_per_point(cg_log, frames_txt):
    """Instructions per drawn point of a tests/bench/callgrind_frames.c run under callgrind: the
    instructions valgrind's log counted over the sum of points drawn that the program printed."""
    refs = int(re.search(r"refs:\s+([\d,]+)", open(cg_log).read()).group(1).replace(",", ""))
    pts = int(re.search(r"points drawn \(sum\): (\d+)", open(frames_txt).read()).group(1))
    return refs / pts


def rounds(path):
    """A side-by-side benchmark's rounds, one line of numbers each (tests/bench/*_select.sh,
    flat_squares.sh), and the median over rounds of column k."""
    rows = [list(map(float, line.split())) for line in open(path) if line.strip()]
    return rows, lambda k: statistics.median(r[k] for r in rows)


def cg_lines(path, srcdir, n):
    total, lines, funcs = cg_parse(path)
    out = []
    out.append("| Ir (self) | share | function |")
    out.append("|---:|---:|---|")
    for fn, ir in sorted(funcs.items(), key=lambda kv: -kv[1])[:8]:
        out.append("| %s | %.1f%% | `%s` |" % (f"{ir:,}", 100.0 * ir / total, fn))
    out.append("")
    out.append("| Ir (self) | share | file:line | source |")
    out.append("|---:|---:|---|---|")
    cache = {}
    for (fname, ln), ir in sorted(lines.items(), key=lambda kv: -kv[1])[:n]:
        text = ""
        base = os.path.basename(fname or "?")
        for cand in (fname, os.path.join(srcdir, "src", base), os.path.join(srcdir, "include", "modelc", base)):
            if cand and os.path.isfile(cand):
                if cand not in cache:
                    with open(cand, errors="replace") as f:
                        cache[cand] = f.read().split("\n")
                src = cache[cand]
                if 0 < ln <= len(src):
                    text = src[ln - 1].strip()
                break
        text = text.replace("|", "\\|")
        out.append("| %s | %.1f%% | %s:%d | `%s` |" % (f"{ir:,}", 100.0 * ir / total, base, ln, text))
    print("\n".join(out))


# ---- Draco check ---------------------------------------------------------------------------------

def read_ply(path):
    """Vertices (x, y, z) of an ASCII or binary little-endian PLY with float/uchar properties."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"\n", data.index(b"end_header")) + 1
    header = data[:end].decode("ascii", "replace").split("\n")
    fmt, count, props, in_vertex = None, 0, [], False
    for h in header:
        w = h.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            in_vertex = w[1] == "vertex"
            if in_vertex:
                count = int(w[2])
        elif w[0] == "property" and in_vertex:
            props.append((w[1], w[2]))
    names = [p[1] for p in props]
    ix, iy, iz = names.index("x"), names.index("y"), names.index("z")
    body = data[end:]
    pts = []
    if fmt == "ascii":
        rows = body.decode().split("\n")
        for r in rows[:count]:
            v = r.split()
            pts.append((float(v[ix]), float(v[iy]), float(v[iz])))
    else:
        codes = {"float": "f", "float32": "f", "uchar": "B", "uint8": "B", "int": "i", "int32": "i",
                 "double": "d", "ushort": "H", "short": "h", "uint": "I", "char": "b"}
        st = struct.Struct("<" + "".join(codes[t] for t, _ in props))
        for i in range(count):
            v = st.unpack_from(body, i * st.size)
            pts.append((v[ix], v[iy], v[iz]))
    return pts


def ply_check(orig, decoded):
    a = read_ply(orig)
    b = read_ply(decoded)
    sa = {(round(x), round(y), round(z)) for x, y, z in a}
    maxerr = max((max(abs(x - round(x)), abs(y - round(y)), abs(z - round(z))) for x, y, z in b), default=0)
    sb = {(round(x), round(y), round(z)) for x, y, z in b}
    same = len(a) == len(b) and sa == sb
    print("points %d decoded %d distinct %d/%d max_offgrid %.4f lossless %s"
          % (len(a), len(b), len(sa), len(sb), maxerr, "yes" if same else "no"))


# ---- image comparison ---------------------------------------------------------------------------

def pnm_body(path):
    with open(path, "rb") as f:
        d = f.read()
    return d.split(b"\n", 3)[3]


def image_cmp(a_ppm, b_ppm, a_pgm, b_pgm):
    a, b = pnm_body(a_ppm), pnm_body(b_ppm)
    ma, mb = pnm_body(a_pgm), pnm_body(b_pgm)
    if a == b and ma == mb:
        print("identical")
        return
    cov = sum(1 for x, y in zip(ma, mb) if x != y)
    col = sum(1 for i in range(0, len(a), 3) if a[i:i + 3] != b[i:i + 3])
    drawn = sum(1 for x in ma if x)
    print(f"{col} of {drawn} pixels differ ({cov} in coverage)")


# ---- report --------------------------------------------------------------------------------------

def kv(path):
    """'key: value' lines of a program's output."""
    d = {}
    if not os.path.isfile(path):
        return d
    with open(path) as f:
        for line in f:
            if ":" in line:
                k, v = line.split(":", 1)
                d[k.strip()] = v.strip()
    return d


def num(s):
    m = re.search(r"[-+]?\d+(\.\d+)?", s or "")
    return float(m.group(0)) if m else float("nan")


def read(path, default=""):
    try:
        with open(path) as f:
            return f.read().strip()
    except OSError:
        return default


def fmt_int(v):
    return f"{int(round(v)):,}"


def report(rdir, out_md):
    meta = kv(os.path.join(rdir, "meta.txt"))
    depths = [int(d) for d in meta["depths"].split()]
    rounds = int(meta["rounds"])
    frames = int(meta["frames"])
    cg_frames = int(meta["cg_frames"])
    size = meta["size"]
    target_d = int(meta.get("target_depth", "8"))
    R = {}
    for d in depths:
        p = lambda name: os.path.join(rdir, f"d{d}.{name}")
        b = json.load(open(p("budget.json")))
        r = {"budget": b}
        # a round's modelc time: the mean of the runs before and after Mesa (A-B-A).
        # kinds: the viewer (wall clock), callgrind_frames --time (wall and CPU), Mesa (wall and CPU)
        series = {"nofinish": ("nofinish", "ms per frame (median)"), "finish": ("finish", "ms per frame (median)"),
                  "cpu_nofinish": ("cpu.nofinish", "cpu ms per frame (median)"),
                  "cpu_finish": ("cpu.finish", "cpu ms per frame (median)"),
                  "mesa": ("mesa", "ms per frame (median)"), "mesa_cpu": ("mesa", "cpu ms per frame (median)")}
        for kind, (stem, key) in series.items():
            ms = []
            for i in range(1, rounds + 1):
                runs = [kv(p(f"{stem}.r{i}.txt"))] if stem == "mesa" else \
                       [kv(p(f"{stem}.r{i}.a.txt")), kv(p(f"{stem}.r{i}.b.txt"))]
                ms.append(statistics.mean(num(o.get(key)) for o in runs))
            r[kind + "_ms_all"] = ms
            r[kind + "_ms"] = statistics.median(ms)
        n_pts = b["points"]
        r["drawn"] = num(kv(p("nofinish.r1.a.txt")).get("points drawn per frame"))
        for kind in ("nofinish", "finish", "cpu_nofinish", "cpu_finish"):
            r[kind + "_mps"] = r["drawn"] / r[kind + "_ms"] / 1e3
        r["mesa_cpu_mps"] = n_pts / r["mesa_cpu_ms"] / 1e3
        ratios = lambda a, b: [x / y for x, y in zip(r[a + "_ms_all"], r[b + "_ms_all"])]
        r["ratio_wall_all"] = ratios("mesa", "nofinish")
        r["ratio_cpu_all"] = ratios("mesa_cpu", "cpu_nofinish")
        r["ratio_cpu_finish_all"] = ratios("mesa_cpu", "cpu_finish")
        r["ratio_wall"] = statistics.median(r["ratio_wall_all"])
        r["ratio"] = statistics.median(r["ratio_cpu_all"])
        r["ratio_finish"] = statistics.median(r["ratio_cpu_finish_all"])
        mesa0 = kv(p("mesa.r1.txt"))
        r["renderer"] = mesa0.get("renderer", "?")
        r["gl_version"] = mesa0.get("version", "?")
        r["lp_threads"] = mesa0.get("LP_NUM_THREADS", "?")
        r["depth_bits"] = mesa0.get("depth bits", "?")
        for view in ("turn", "front"):
            o = kv(p(f"cg.{view}.txt"))
            r[f"cg_{view}_points"] = num(o.get("points drawn (sum)"))
            r[f"cg_{view}_frames"] = num(o.get("frames"))
            t = kv(p(f"cg.{view}.total"))
            r[f"cg_{view}_ir"] = num(t.get("Ir"))
            r[f"cg_{view}_bc"] = num(t.get("Bc"))
            r[f"cg_{view}_bcm"] = num(t.get("Bcm"))
            r[f"cg_{view}_bi"] = num(t.get("Bi"))
            r[f"cg_{view}_bim"] = num(t.get("Bim"))
        pm, pg = kv(p("pixels.modelc.txt")), kv(p("pixels.mesa.txt"))
        r["px_modelc"] = num(next((v for k, v in pm.items() if k.startswith("pixels covered per view")), ""))
        r["px_mesa"] = num(next((v for k, v in pg.items() if k.startswith("pixels covered per view")), ""))
        r["img_front"] = read(p("image.front.cmp"), "?")
        r["img_rot"] = read(p("image.rot.cmp"), "?")
        for cl in ("cl7", "cl10", "rgb.cl10"):
            r["draco_" + cl] = num(read(p(f"draco.{cl}.bytes")))
        r["draco_check"] = read(p("draco.check"), "?")
        r["bake_s"] = read(p("bake.seconds"), "?")
        R[d] = r

    L = []
    A = L.append
    A("# modelc benchmarks")
    A("")
    A(f"Written by `tests/bench/run.sh` (`make bench`) on {meta['date']}. Do not edit by hand: run it again.")
    A("")
    A("## Machine and tools")
    A("")
    A(f"- machine: {meta['cpu']}, nproc {meta['nproc']}, {meta['mem']}; load average at start {meta['load_start']}, at end {meta.get('load_end', '?')}")
    A(f"- kernel: {meta['kernel']}")
    A(f"- compiler: {meta['cc_version']}")
    A(f"- valgrind: {meta['valgrind']}; Mesa: {meta['mesa_pkg']}; draco: {meta['draco_pkg']}")
    A(f"- OpenGL renderer (glGetString(GL_RENDERER)): **{R[depths[0]]['renderer']}**, GL_VERSION {R[depths[0]]['gl_version']}, LP_NUM_THREADS={R[depths[0]]['lp_threads']}, {R[depths[0]]['depth_bits']}-bit depth buffer")
    A(f"- source tree: commit {meta['commit']}; runtime/ {meta['runtime_state']} (benchmarked copy: `{meta['snapshot']}`, octree_render.c sha256 {meta['render_sha']})")
    A(f"- generator: `{meta['modelc']}` ({meta['modelc_version']}); model `{meta['model_src']}` baked with `--depth D`, one bake per depth")
    A(f"- views: {size}, orthographic, zoom 1, pitch = roll = 0; a full turn of yaw starting frontal (yaw 0): "
      f"frame i of N at yaw = i * 4096 / N modelc angle units. Each run reports the median over {frames} frames; "
      f"there are {rounds} rounds per depth, each A-B-A: modelc (without, then with finishing), Mesa, modelc again. "
      "A round's modelc time is the mean of its two runs; tables show the median over rounds, and a speed ratio "
      "is the median over rounds of Mesa's time / modelc's time in the same round.")
    A("- clocks: wall-clock times are what the viewer's `--bench` prints. `callgrind_frames --time` runs the same "
      "loop (mc_clear + mc_octree_render [+ mc_finish_pixel_holes], same object code) and `osmesa_points` its own, both "
      "printing the median wall-clock **and process CPU time** per frame. On a machine shared with other work a "
      "~30 ms Mesa frame is preempted far more often than a ~1 ms modelc frame, which inflates Mesa's wall-clock "
      "median and the wall-clock ratio; the CPU-time ratio is not affected by that, so it is the headline figure. "
      "On an idle machine the two agree.")
    loads = [float(x) for x in read(os.path.join(rdir, "load.txt"), "").split()]
    if loads:
        A("")
        A(f"- 1-minute load average during the timings: {min(loads):.2f} to {max(loads):.2f} (the benchmark itself adds about 1)."
          + (" **The machine was shared with other work while this ran: absolute times are inflated and noisier than on "
             "an idle machine; the CPU-time ratios are the reliable figures.**" if max(loads) > 1.6 else ""))
    A("")

    A("## 1. Size and speed of modelc")
    A("")
    A("Data bytes are the bake's `budget.json` `flash` figures (masks of levels 0..D-1, colours of levels 1..D, "
      "palette). Geometry bits per point = masks only; total = masks + colours + palette. ms per frame: wall clock "
      f"from the viewer's `--bench {frames}` (mc_clear + mc_octree_render [+ mc_finish_pixel_holes]), and CPU time of the "
      "same loop from `callgrind_frames --time`. Mpoints/s = points drawn per frame / wall-clock ms.")
    A("")
    A("| depth | points | masks B | colours B | palette B | data bytes | geometry bits/pt | total bits/pt | ms/frame (no finish) | ms/frame (finish) | CPU ms/frame (no finish) | CPU ms/frame (finish) | Mpoints/s (no finish) | Mpoints/s (finish) |")
    A("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for d in depths:
        r, b = R[d], R[d]["budget"]
        fl = b["flash"]
        A(f"| {d} | {fmt_int(b['points'])} | {fmt_int(fl['masks'])} | {fmt_int(fl['colors'])} | {fmt_int(fl['palette'])} | "
          f"{fmt_int(fl['total'])} | {b['bits_per_point']['geometry']:.3f} | {b['bits_per_point']['total']:.3f} | "
          f"{r['nofinish_ms']:.3f} | {r['finish_ms']:.3f} | {r['cpu_nofinish_ms']:.3f} | {r['cpu_finish_ms']:.3f} | "
          f"{r['nofinish_mps']:.1f} | {r['finish_mps']:.1f} |")
    A("")
    A("Per-round viewer medians (ms, no finish / finish): " + "; ".join(
        f"d{d}: " + ", ".join(f"{a:.3f}" for a in R[d]["nofinish_ms_all"]) + " / " +
        ", ".join(f"{a:.3f}" for a in R[d]["finish_ms_all"]) for d in depths) + ".")
    A("")

    A("## 2. Instructions per drawn point (callgrind)")
    A("")
    A(f"`tests/bench/callgrind_frames.c` renders {cg_frames} views of the turn (and, separately, the frontal view "
      "alone) with mc_clear + mc_octree_render; `valgrind --tool=callgrind --toggle-collect=mc_octree_render` counts only "
      "instructions inside mc_octree_render and its callees. Ir per point = that total / sum of mc_stats.points. "
      "Same object code as the timed viewer. `--branch-sim=yes` also simulates a simple branch predictor: "
      "mispredicted conditional branches (Bcm) and indirect jumps (Bim, e.g. switch jump tables) are valgrind's "
      "model, not this CPU's, but are deterministic and show what the instruction count leaves out (a mispredict "
      "costs some 15-20 cycles, several instructions' worth).")
    A("")
    A(f"| depth | points drawn per frame | Ir per point ({cg_frames}-view turn) | Ir per frame (turn) | Ir per point (frontal) | Ir per frame (frontal) | cond. branches per point | mispredicted per point (sim.) | indirect jumps per point | mispredicted per point (sim.) | all mispredicts per point |")
    A("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for d in depths:
        r = R[d]
        ipp = r["cg_turn_ir"] / r["cg_turn_points"]
        ipf = r["cg_turn_ir"] / r["cg_turn_frames"]
        fpp = r["cg_front_ir"] / r["cg_front_points"]
        fpf = r["cg_front_ir"] / r["cg_front_frames"]
        r["ir_per_point"] = ipp
        n = r["cg_turn_points"]
        bc, bcm, bi, bim = (r[f"cg_turn_{e}"] / n for e in ("bc", "bcm", "bi", "bim"))
        A(f"| {d} | {fmt_int(n / r['cg_turn_frames'])} | {ipp:.2f} | {fmt_int(ipf)} | {fpp:.2f} | {fmt_int(fpf)} | "
          f"{bc:.2f} | {bcm:.3f} | {bi:.2f} | {bim:.3f} | {bcm + bim:.3f} |")
    A("")
    A("Depths 6 and 7 cost more per point because their leaves are larger than a pixel at this size (a cell of "
      "depth d spans 240 / 2^d pixels: 3.75 at depth 6, 1.9 at depth 7): the default zoom footprint (config.h "
      "MC_SPLAT_DEFAULT_MODE) draws each leaf as a 4x4 or 2x2 square through the checked leaf path, and a point "
      "here is a leaf, not a pixel. Depths 8 and 9 draw one pixel per leaf on the unchecked path.")
    A("")
    clear_ir = num(kv(os.path.join(rdir, "clear.cg.total")).get("Ir"))
    if clear_ir == clear_ir:
        A(f"Not counted above: mc_clear costs {fmt_int(clear_ir)} Ir per {size} frame "
          f"({clear_ir / (int(size.split('x')[0]) * int(size.split('x')[1])):.2f} per pixel), and is in the timed frames of section 1.")
        A("")
    lines_md = read(os.path.join(rdir, f"d{target_d}.cg.lines.md"))
    if lines_md:
        A(f"Where mc_octree_render's instructions go at depth {target_d} ({cg_frames}-view turn; self cost, inlined code "
          "attributed to its source line; full listing in "
          f"`build/bench/results/d{target_d}.cg.annotate.txt`):")
        A("")
        A(lines_md)
        A("")

    A("## 3. modelc vs Mesa software OpenGL (OSMesa, llvmpipe, one thread)")
    A("")
    A("`tests/bench/osmesa_points.c` decodes the same bake's leaf cells (double precision, independently of the "
      "runtime), uploads them once into a VBO (float xyz + RGBA8 colour per point, in mc_octree_render's draw order) and "
      f"draws them as one-pixel GL_POINTS, depth test GL_LESS, {size}, orthographic projection matching modelc's view. "
      f"Timed per frame: glClear + modelview + glDrawArrays + glFinish, median over the same {frames}-frame turn. "
      "Ratio = median over rounds of Mesa ms / modelc ms (without finishing unless stated) in the same round; "
      "**CPU ratio** = process CPU times (Mesa vs callgrind_frames --time), wall ratio = wall clock (Mesa vs the "
      "viewer's --bench). Pixels: mean pixels drawn over the "
      f"{cg_frames} views of the turn (modelc without finishing). Images: modelc's frame (no finishing) compared "
      f"pixel by pixel with Mesa's, frontal and at yaw {meta.get('rot_yaw', '?')} units (frame 3 of a 20-frame turn); "
      "both are kept in `build/bench/results/` as PPM.")
    A("")
    A("| depth | points | modelc CPU ms | Mesa CPU ms | **CPU ratio** | CPU ratio, modelc with finishing | modelc wall ms | Mesa wall ms | wall ratio | Mesa Mpoints/s (CPU) | pixels modelc | pixels Mesa | frontal image | rotated image |")
    A("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|")
    for d in depths:
        r = R[d]
        A(f"| {d} | {fmt_int(r['budget']['points'])} | {r['cpu_nofinish_ms']:.3f} | {r['mesa_cpu_ms']:.3f} | "
          f"**{r['ratio']:.1f}x** | {r['ratio_finish']:.1f}x | {r['nofinish_ms']:.3f} | {r['mesa_ms']:.3f} | "
          f"{r['ratio_wall']:.1f}x | {r['mesa_cpu_mps']:.1f} | {fmt_int(r['px_modelc'])} | "
          f"{fmt_int(r['px_mesa'])} | {r['img_front']} | {r['img_rot']} |")
    A("")
    A("Per-round Mesa medians (CPU / wall ms): " + "; ".join(
        f"d{d}: " + ", ".join(f"{a:.2f}" for a in R[d]["mesa_cpu_ms_all"]) + " / " +
        ", ".join(f"{a:.2f}" for a in R[d]["mesa_ms_all"]) for d in depths) + ".")
    A("")
    A("Per-round ratios (CPU / wall): " + "; ".join(
        f"d{d}: " + ", ".join(f"{a:.1f}" for a in R[d]["ratio_cpu_all"]) + " / " +
        ", ".join(f"{a:.1f}" for a in R[d]["ratio_wall_all"]) for d in depths) + ".")
    A("")

    A("## 4. Geometry size vs Draco")
    A("")
    A("The same leaf cells' integer coordinates (0..2^D-1 per axis) written as an ASCII PLY point cloud and encoded "
      "with `draco_encoder -point_cloud -qp D` at the default compression level (7) and at `-cl 10`; bits per point "
      "= 8 * bytes / points. modelc geometry = the masks. Lossless = `draco_decoder` output rounds back to exactly "
      "the same set of cells. Last columns: Draco with the palette colours as an RGB attribute vs modelc's total.")
    A("")
    A("| depth | points | modelc masks B | modelc geometry bits/pt | Draco B (cl 7) | bits/pt (cl 7) | Draco B (cl 10) | bits/pt (cl 10) | Draco / modelc | lossless | Draco+RGB B (cl 10) | bits/pt | modelc total bits/pt |")
    A("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|")
    for d in depths:
        r, b = R[d], R[d]["budget"]
        n = b["points"]
        lossless = "yes" if "lossless yes" in r["draco_check"] else "NO (" + r["draco_check"] + ")"
        r["draco_bpp"] = 8 * r["draco_cl10"] / n
        A(f"| {d} | {fmt_int(n)} | {fmt_int(b['flash']['masks'])} | {b['bits_per_point']['geometry']:.3f} | "
          f"{fmt_int(r['draco_cl7'])} | {8 * r['draco_cl7'] / n:.3f} | {fmt_int(r['draco_cl10'])} | {r['draco_bpp']:.3f} | "
          f"{r['draco_cl10'] / b['flash']['masks']:.2f}x | {lossless} | {fmt_int(r['draco_rgb.cl10'])} | "
          f"{8 * r['draco_rgb.cl10'] / n:.3f} | {b['bits_per_point']['total']:.3f} |")
    A("")

    A("## Summary")
    A("")
    if target_d in R:
        r = R[target_d]
        b = r["budget"]
        geo = b["bits_per_point"]["geometry"]
        ok = lambda c: "meets" if c else "misses"
        ratio, ipp = r["ratio"], r["ir_per_point"]
        A(f"At depth {target_d} ({fmt_int(b['points'])} points) and {size}, modelc draws a frame of the turn in "
          f"{r['cpu_nofinish_ms']:.3f} ms of CPU time ({r['cpu_finish_ms']:.3f} ms with finishing; the viewer's wall-clock "
          f"median is {r['nofinish_ms']:.3f} ms) against {r['mesa_cpu_ms']:.3f} ms for Mesa single-thread "
          f"({r['renderer']}; {r['mesa_ms']:.3f} ms wall clock) drawing the same cells to the same pixels: "
          f"**{ratio:.1f}x faster** ({r['ratio_finish']:.1f}x with finishing; wall-clock ratio {r['ratio_wall']:.1f}x), "
          f"which **{ok(ratio >= 30)}** the >= 30x target"
          + ("" if ratio >= 30 else f" (short by a factor {30 / ratio:.2f}: modelc would need {r['mesa_cpu_ms'] / 30:.3f} ms per frame)")
          + f". mc_octree_render executes **{ipp:.1f} instructions per drawn point** ({fmt_int(r['cg_turn_ir'] / r['cg_turn_frames'])} per frame), "
          f"which **{ok(ipp <= 25)}** the <= 25 Ir/point target"
          + ("" if ipp <= 25 else f" ({ipp - 25:.1f} Ir/point too many, {ipp / 25:.2f}x the target)")
          + f". Geometry costs **{geo:.2f} bits per point** (masks only; {b['bits_per_point']['total']:.2f} with colours), "
          f"which **{ok(geo <= 3)}** the <= 3 bits/point target"
          + ("" if geo <= 3 else f" (over by {geo - 3:.2f} bits/point)")
          + f"; Draco at its best setting needs {r['draco_bpp']:.2f} bits/point for the same cells."
          + (f" Timings were taken on a shared machine (1-minute load {min(loads):.1f} to {max(loads):.1f} on "
             f"{meta['nproc']} CPUs); per-round CPU-time ratios at depth {target_d} ranged "
             f"{min(r['ratio_cpu_all']):.1f}x to {max(r['ratio_cpu_all']):.1f}x, wall-clock ratios "
             f"{min(r['ratio_wall_all']):.1f}x to {max(r['ratio_wall_all']):.1f}x." if loads and max(loads) > 1.6 else ""))
    A("")

    A("## Commands")
    A("")
    A("Every command the run executed, in order (repeats counted; output redirections omitted), from the repository root:")
    A("")
    A("<details><summary>commands</summary>")
    A("")
    A("```")
    with open(os.path.join(rdir, "commands.log")) as f:
        cmds = [c.rstrip("\n") for c in f if c.strip()]
    seen, order = {}, []
    for c in cmds:
        if c not in seen:
            seen[c] = 0
            order.append(c)
        seen[c] += 1
    for c in order:
        A(c + (f"    # x{seen[c]}" if seen[c] > 1 else ""))
    A("```")
    A("")
    A("</details>")
    A("")
    # sections other scripts own (make bench-firmware: tests/fw/bench.sh, make bench-accuracy:
    # tests/accuracy/bench.sh) survive a rerun
    keep = ""
    if os.path.exists(out_md):
        text = open(out_md).read()
        for owner in ("bench-firmware", "bench-accuracy"):
            m = re.search(r"<!-- %s: begin -->.*?<!-- %s: end -->\n?" % (owner, owner), text, re.S)
            keep += m.group(0) if m else ""
    with open(out_md, "w") as f:
        f.write("\n".join(L))
        if keep:
            f.write("\n" + keep)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    cmd, args = sys.argv[1], sys.argv[2:]
    if cmd == "cg-total":
        cg_total(args[0])
    elif cmd == "ir-per-point":
        print(f"{ir_per_point(args[0], args[1]):.4f}")
    elif cmd == "cg-lines":
        cg_lines(args[0], args[1], int(args[2]))
    elif cmd == "ply-check":
        ply_check(args[0], args[1])
    elif cmd == "image-cmp":
        image_cmp(*args[:4])
    elif cmd == "report":
        report(args[0], args[1])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
