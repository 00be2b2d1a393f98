#!/usr/bin/env python3
"""make bench-accuracy report (tests/accuracy/bench.sh):

  report.py VIEWS_CSV CG_CSV OUT_CSV PLOT_DIR RESULTS_MD [--frames N] [--size WxH] [--seconds S]

Aggregates the per-view rows of acc.c into one row per setting (model, depth, build, frac, lod, splat,
fill; lod the level-selection bound in pixels, mc_octree_options.max_error / 16, 0 = off): means over the 12 views of PSNR, SSIM, coverage difference, median ms and CPU ms per frame,
PSNR at zoom 1 and zoom 2 separately, and instructions per frame from callgrind where counted. Marks
the Pareto front per model (error against time: a setting is on the front when no other setting of
the same model is at least as fast and at least as accurate and better in one of the two by more than
the noise: 0.05 dB PSNR, or 5 % of the time), writes OUT_CSV, a gnuplot script and its data under
PLOT_DIR, and the bench-accuracy section of RESULTS_MD (kept by tests/bench/bench_tools.py).
"""
import argparse
import csv
import math
import os
import re
import statistics
import sys
from collections import defaultdict

EPS_DB, EPS_TIME = 0.05, 0.05
BEGIN, END = "<!-- bench-accuracy: begin -->", "<!-- bench-accuracy: end -->"
BUILD_TAG = {"fixed": "", "float": "f", "exact": "x"}   # plot labels: d8f = depth 8, float build


def config_defaults():
    text = open("runtime/include/modelc/config.h").read()
    def get(name, dflt):
        m = re.search(r"#define\s+%s\s+(\d+)" % name, text)
        return int(m.group(1)) if m else dflt
    splat = {1: "pixel", 2: "zoom"}.get(get("MC_SPLAT_DEFAULT_MODE", 1), "pixel")
    fill = {0: "none", 1: "pixel", 2: "scanline"}.get(get("MC_FILL_DEFAULT_MODE", 1), "pixel")
    cat = open("models/catalogue.mk").read()
    m = re.search(r"bunny00\.opts\s*:=.*--depth\s+(\d+)", cat)
    return {"depth": int(m.group(1)) if m else 8, "frac": get("MC_FRAC_BITS", 15), "splat": splat, "fill": fill,
            "build": "fixed", "lod": 0}


def lod_level(depth, lod, zoom, size):
    """The level mc_octree_lod_depth draws (orthographic): the least l >= 1, at most depth, whose node side
    zoom * min(w, h) / 2^l is at most lod pixels; depth when lod is 0."""
    if not lod:
        return depth
    side = zoom * min(size)
    l = 1
    while l < depth and side / 2 ** l > lod:
        l += 1
    return l


def lod_tag(lod):
    return f"{lod:g}"


def dominates(a, b, cost="cpu_ms", eps=EPS_TIME):
    """a at least as cheap as b and at least as accurate (PSNR), and better in one by more than the
    noise (eps of the cost, EPS_DB of PSNR)."""
    if a[cost] == "" or b[cost] == "":
        return False
    if a[cost] > b[cost] * (1 + eps) or a["psnr"] < b["psnr"] - EPS_DB:
        return False
    return a[cost] < b[cost] * (1 - eps) or a["psnr"] > b["psnr"] + EPS_DB


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("views"); ap.add_argument("cg"); ap.add_argument("out_csv"); ap.add_argument("plot_dir")
    ap.add_argument("results_md")
    ap.add_argument("--frames", default="7"); ap.add_argument("--size", default="320x240")
    ap.add_argument("--seconds", default="?")
    a = ap.parse_args()
    dflt = config_defaults()

    rows = list(csv.DictReader(open(a.views)))
    groups = defaultdict(list)
    status = {}
    for r in rows:
        key = (r["model"], int(r["depth"]), r["build"], int(r["frac"]), float(r["lod"] or 0), r["splat"], r["fill"])
        if r["status"] != "ok":
            status[key[:5]] = r["status"]
            continue
        groups[key].append(r)

    cg = defaultdict(dict)
    for r in csv.DictReader(open(a.cg)):
        cg[(r["model"], int(r["depth"]), r["build"], int(r["frac"]), float(r["lod"] or 0))][r["part"]] = int(r["ir"])

    out = []
    for key, rs in sorted(groups.items()):
        m, d, build, f, lod, splat, fill = key
        mean = lambda k, sel=rs: statistics.fmean(float(r[k]) for r in sel)
        z1 = [r for r in rs if float(r["zoom"]) == 1]
        z2 = [r for r in rs if float(r["zoom"]) == 2]
        c = cg.get(key[:5], {})
        ir = ""
        if c and f"acc_render_{splat}" in c:
            # acc.c --cg: 4 views x splats clears, 4 renders per splat, 4 fills per fill and splat
            n_clear = 4 * (2 if "acc_render_zoom" in c else 1)
            ir = c.get("acc_clear", 0) / n_clear + c[f"acc_render_{splat}"] / 4
            if fill != "none":
                ir += c.get(f"acc_fill_{fill}_{splat}", 0) / 4
            ir = round(ir)
        out.append({"model": m, "depth": d, "build": build, "frac": f, "lod": lod, "splat": splat, "fill": fill,
                    "views": len(rs), "psnr": mean("psnr"), "ssim": mean("ssim"), "coverage": mean("coverage"),
                    "psnr_zoom1": mean("psnr", z1) if z1 else float("nan"),
                    "psnr_zoom2": mean("psnr", z2) if z2 else float("nan"),
                    "ssim_zoom2": mean("ssim", z2) if z2 else float("nan"),
                    "ms": mean("ms"), "cpu_ms": mean("cpu_ms"), "ir_per_frame": ir})
    for r in out:
        r["default"] = int(all(r[k] == dflt[k] for k in ("depth", "frac", "splat", "fill", "build", "lod")))
        same = [o for o in out if o["model"] == r["model"]]
        r["pareto"] = int(not any(dominates(o, r) for o in same if o is not r))
        r["dominated_by"] = ""
        if not r["pareto"]:
            best = max((o for o in same if dominates(o, r)), key=lambda o: o["psnr"])
            r["dominated_by"] = (f"d{best['depth']} {best['build']} F{best['frac']}"
                                 f"{' bound ' + lod_tag(best['lod']) + ' px' if best['lod'] else ''} {best['splat']}/{best['fill']}")
        # the same against instructions per frame (exact, where counted; 1 % counts as a difference)
        r["pareto_ir"] = "" if r["ir_per_frame"] == "" else int(
            not any(dominates(o, r, "ir_per_frame", 0.01) for o in same if o is not r))

    cols = ["model", "depth", "build", "frac", "lod", "splat", "fill", "views", "psnr", "ssim", "coverage", "psnr_zoom1",
            "psnr_zoom2", "ssim_zoom2", "ms", "cpu_ms", "ir_per_frame", "pareto", "pareto_ir", "default",
            "dominated_by"]
    with open(a.out_csv, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(cols + ["status"])
        for r in out:
            w.writerow([lod_tag(r[k]) if k == "lod" else f"{r[k]:.4f}" if isinstance(r[k], float) else r[k]
                        for k in cols] + ["ok"])
        for (m, d, build, f, lod), st in sorted(status.items()):
            w.writerow([m, d, build, f, lod_tag(lod)] + [""] * (len(cols) - 5) + [st])

    # ---- plot --------------------------------------------------------------------------------------
    os.makedirs(a.plot_dir, exist_ok=True)
    models = sorted({r["model"] for r in out}, key=lambda m: (m != "bunny00", m))
    series = [("fixed F15", lambda r: r["build"] == "fixed" and r["frac"] == 15 and not r["lod"], 7, "#1f77b4"),
              ("fixed F15 with a level-selection bound", lambda r: r["lod"] > 0, 5, "#ff7f0e"),
              ("fixed, other F", lambda r: r["build"] == "fixed" and r["frac"] != 15, 1, "#999999"),
              ("float build", lambda r: r["build"] == "float", 9, "#2ca02c"),
              ("exact (double walk)", lambda r: r["build"] == "exact", 13, "#9467bd")]
    for m in models:
        for i, (_, sel, _, _) in enumerate(series):
            with open(f"{a.plot_dir}/{m}_{i}.dat", "w") as fh:
                for r in out:
                    if r["model"] == m and sel(r):
                        fh.write(f"{r['cpu_ms']:.5f} {r['psnr']:.4f}\n")
        front = sorted((r for r in out if r["model"] == m and r["pareto"]), key=lambda r: r["cpu_ms"])
        with open(f"{a.plot_dir}/{m}_front.dat", "w") as fh:
            for r in front:
                fh.write(f"{r['cpu_ms']:.5f} {r['psnr']:.4f}\n")
        # labels of the front, thinned so that they do not overprint: depth, F unless 15, f for float,
        # x for exact, eN for a level-selection bound of N pixels, splat and fill initials (zn: zoom splat, no fill)
        with open(f"{a.plot_dir}/{m}_labels.dat", "w") as fh:
            last = None
            for r in front:
                if last and abs(math.log10(r["cpu_ms"] / last[0])) < 0.15 and abs(r["psnr"] - last[1]) < 1.5:
                    continue
                last = (r["cpu_ms"], r["psnr"])
                fh.write(f"{r['cpu_ms']:.5f} {r['psnr']:.4f} d{r['depth']}{BUILD_TAG[r['build']]}"
                         f"{'' if r['frac'] == 15 else 'F' + str(r['frac'])}{'e' + lod_tag(r['lod']) if r['lod'] else ''}"
                         f":{r['splat'][0]}{r['fill'][0]}\n")
        with open(f"{a.plot_dir}/{m}_default.dat", "w") as fh:
            for r in out:
                if r["model"] == m and r["default"]:
                    fh.write(f"{r['cpu_ms']:.5f} {r['psnr']:.4f}\n")
    gp = [f'set terminal pngcairo size {560 * len(models)},580 font ",10"',
          f'set output "{a.plot_dir}/accuracy.png"',
          f"set multiplot layout 1,{len(models)}",
          "set logscale x", "set grid", 'set xlabel "ms per frame (median thread CPU time, mean over the views)"',
          'set ylabel "PSNR against the mesh reference (dB, mean of 12 views)"', "set key below maxrows 2", "set yrange [0:*]"]
    for m in models:
        gp.append(f'set title "{m}, {a.size}: PSNR against time per setting (depth, F, build, splat, fill)"')
        plots = []
        for i, (label, _, pt, colour) in enumerate(series):
            plots.append(f'"{a.plot_dir}/{m}_{i}.dat" using 1:2 with points pt {pt} ps 0.8 lc rgb "{colour}" '
                         f'title "{label}"')
        plots.append(f'"{a.plot_dir}/{m}_front.dat" using 1:2 with linespoints lw 2 pt 6 ps 1.6 lc rgb "#d62728" '
                     'title "Pareto front"')
        plots.append(f'"{a.plot_dir}/{m}_labels.dat" using 1:2:3 with labels offset 2.2,-0.8 font ",8" notitle')
        plots.append(f'"{a.plot_dir}/{m}_default.dat" using 1:2 with points pt 3 ps 3 lw 2 lc rgb "black" '
                     'title "default (d8 F15 zoom splat, scanline fill)"')
        gp.append("plot " + ", \\\n     ".join(plots))
    gp.append("unset multiplot")
    open(f"{a.plot_dir}/accuracy.gp", "w").write("\n".join(gp) + "\n")

    # ---- RESULTS.md section -------------------------------------------------------------------------
    L = [BEGIN, "## Run time against error (make bench-accuracy)", ""]
    L.append(f"Written by `tests/accuracy/bench.sh` (`make bench-accuracy`, {a.seconds} s on this machine). "
             f"Data: `tests/bench/accuracy.csv` (one row per setting), plot `tests/bench/accuracy.png`; the per-view "
             f"rows stay in `build/bench/accuracy/views.csv`.")
    meta = os.path.join(os.path.dirname(a.views), "meta.txt")
    if os.path.exists(meta):
        kv = dict(line.split(": ", 1) for line in open(meta).read().splitlines() if ": " in line)
        L.append(f"Run {kv.get('date', '?')} at commit {kv.get('commit', '?')} (runtime sources "
                 f"{kv.get('runtime sources', '?')}), load average at the start {kv.get('load', '?')} on 2 cores.")
    L.append("")
    L.append(f"- Reference: the original mesh, z-buffered triangles in double precision (`runtime/ref/mesh_ref.c`, "
             "from `modelc --dump-reference`: the same unit-cube normalisation as the octree, the same frontal light "
             "of the interpolated vertex normals, each pixel mapped to the bake's own palette). Error: PSNR over RGB "
             "of the whole frame, SSIM of the luminance (11x11 Gaussian window, sigma 1.5), and the share of the "
             "pixels covered by either image that only one covers; each a mean over 12 views: yaw 0/20/40/60 "
             f"degrees (pitch 0/5/10/15) at zoom 1, 1.5 and 2, {a.size}, orthographic.")
    L.append(f"- Cost: median wall-clock ms of mc_clear + render + finish over at least {a.frames} frames (and 20 ms), "
             "mean over the views; instructions per frame (callgrind, the same parts) for every setting, on 4 of the "
             "12 views (yaw 20 and 60 at zoom 1 and 2). The Pareto fronts use CPU time (wall clock counts the time "
             "other processes take the core) and instruction counts. The machine is shared (2 cores, other builds running): times are noisy by 10-30 %, "
             "instruction counts are exact.")
    L.append("- Builds: `fixed` is the runtime compiled with -DMC_FRAC_BITS=F. `float` is the same runtime compiled "
             "with `tests/accuracy/pos_single.h` in place of `runtime/src/pos.h` (config.h MC_POS_HEADER): single-precision screen positions in the same walk, "
             "culling, depth test, footprints and finishing. `exact` is the double-precision octree walk of "
             "`runtime/ref/ref.c` (exact leaf positions from integer cell coordinates) with the runtime's "
             "footprints, a 16-bit depth buffer and the runtime's finishing: the error floor no number format of the "
             "renderer can beat; its time (a matrix product per leaf through a callback) is no target.")
    L.append("- Splat: `pixel` one pixel per leaf (the paper's), `zoom` the footprint that grows with zoom. "
             "Fill: `none`, `pixel` (one-pixel holes), `scanline` (the paper's criterion, hole types 1-4). In the plot "
             "the front's points are labelled dDEPTH[f float, x exact][FBITS unless 15][eBOUND]:SF, S the splat and F the fill "
             "initial (d8:zs = depth 8, zoom splat, scanline fill; d10e2:zs the same at depth 10 with a 2-pixel bound); the "
             "star is the default.")
    size = tuple(int(x) for x in a.size.split("x"))
    zooms = sorted({float(r["zoom"]) for r in rows if r["zoom"]})
    lod_depths = sorted({r["depth"] for r in out if r["lod"]})
    if lod_depths:
        L.append(f"- Level selection: the fixed F = 15 build at depths {', '.join(map(str, lod_depths))} again with "
                 f"`mc_octree_options.max_error` at {', '.join(lod_tag(x) + ' px' for x in sorted({r['lod'] for r in out if r['lod']}))} "
                 "(acc.c `--error PX`, the viewer's `--error PX`): each view draws the shallowest level whose nodes span at most "
                 "the bound, never deeper than the bake (`mc_octree_lod_depth`), so the bound trades error for time at one "
                 "bake; every other setting draws the bake's depth (bound off, the library's default). These settings are "
                 f"points of the same Pareto fronts. At {a.size} a level-l node spans zoom x {min(size)} / 2^l pixels: at "
                 f"depth {lod_depths[-1]} a 1-pixel bound draws level "
                 + ", ".join(f"{lod_level(lod_depths[-1], 1, z, size)} at zoom {z:g}" for z in zooms) + ".")
    L.append("")

    def fmt(r, k, p=2):
        v = r[k]
        return "" if v == "" or v != v else (f"{v:.{p}f}" if isinstance(v, float) else str(v))

    def irs(r):
        return "" if r["ir_per_frame"] == "" else format(r["ir_per_frame"], ",")

    def yes(v):
        return "" if v == "" else ("**yes**" if v else "no")

    def label(r):
        return (f"d{r['depth']} {r['build']}{' F' + str(r['frac']) if r['build'] == 'fixed' else ''}"
                f"{' bound ' + lod_tag(r['lod']) + ' px' if r['lod'] else ''} {r['splat']}/{r['fill']}")

    def lod_table(m, mo):
        """The level-selection bound as an axis: per bake depth that has bounds, the bound off and each bound."""
        depths = sorted({r["depth"] for r in mo if r["lod"]})
        if not depths:
            return
        L.append("")
        L.append(f"### {m}: level-selection bound (fixed point F = 15, {dflt['splat']} splat, {dflt['fill']} fill)")
        L.append("")
        L.append("The bound (`max_error`, pixels) against the bake's depth (bound off), at one bake each; levels = the level "
                 f"drawn at zoom {', '.join(f'{z:g}' for z in zooms)}. The rows with other splats and fills are in the CSV.")
        L.append("")
        L.append("| depth (bake) | bound px | levels drawn | PSNR dB | PSNR zoom 1 | PSNR zoom 2 | SSIM | coverage diff | "
                 "ms (wall) | CPU ms | Ir/frame | Pareto (CPU ms) | Pareto (Ir) |")
        L.append("|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|")
        sel = [r for r in mo if r["build"] == "fixed" and r["frac"] == 15 and r["depth"] in depths
               and r["splat"] == dflt["splat"] and r["fill"] == dflt["fill"]]
        for r in sorted(sel, key=lambda r: (r["depth"], r["lod"])):
            levels = "/".join(str(lod_level(r["depth"], r["lod"], z, size)) for z in zooms)
            L.append(f"| {r['depth']} | {lod_tag(r['lod']) if r['lod'] else 'off'} | {levels} | {r['psnr']:.2f} | "
                     f"{fmt(r, 'psnr_zoom1')} | {fmt(r, 'psnr_zoom2')} | {r['ssim']:.4f} | {100 * r['coverage']:.2f} % | "
                     f"{r['ms']:.3f} | {r['cpu_ms']:.3f} | {irs(r)} | {yes(r['pareto'])} | {yes(r['pareto_ir'])} |")
        L.append("")
        # the deepest bake's bounds against the shallower bakes drawn whole: the same levels, other costs
        d = depths[-1]
        one = [r for r in sel if r["depth"] == d and r["lod"] == 1]
        off = [r for r in sel if r["depth"] == d and not r["lod"]]
        d8 = [r for r in mo if r["default"]]
        if one and off and one[0]["ir_per_frame"] != "" and off[0]["ir_per_frame"] != "":
            o, f_ = one[0], off[0]
            txt = (f"At depth {d} the 1-pixel bound draws {o['psnr']:.2f} dB in {o['ir_per_frame'] / 1e6:.2f} M instructions "
                   f"a frame against {f_['psnr']:.2f} dB in {f_['ir_per_frame'] / 1e6:.2f} M with the bound off "
                   f"({f_['ir_per_frame'] / o['ir_per_frame']:.1f} times the instructions for {f_['psnr'] - o['psnr']:.2f} dB)")
            if d8 and d8[0]["ir_per_frame"] != "":
                g = d8[0]
                txt += (f"; the default (depth {g['depth']}, bound off) {g['psnr']:.2f} dB in {g['ir_per_frame'] / 1e6:.2f} M")
            L.append(txt + ".")
            L.append("")

    for m in models:
        mo = [r for r in out if r["model"] == m]
        L.append(f"### {m}: depth (fixed F = 15, float, exact); splat/fill: none, the default splat alone, the defaults")
        L.append("")
        L.append("| depth | build | splat/fill | PSNR dB | PSNR zoom 1 | PSNR zoom 2 | SSIM | coverage diff | ms (wall) | "
                 "CPU ms | Ir/frame | Pareto (CPU ms) | Pareto (Ir) |")
        L.append("|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---|---|")
        for r in sorted(mo, key=lambda r: (r["depth"], r["build"], r["splat"], r["fill"])):
            if r["frac"] != 15 or r["lod"] or (r["splat"], r["fill"]) not in {(dflt["splat"], dflt["fill"]), (dflt["splat"], "none"),
                                                                   ("pixel", "none"), ("pixel", dflt["fill"])}:
                continue
            L.append(f"| {r['depth']} | {r['build']} | {r['splat']}/{r['fill']} | {fmt(r, 'psnr')} | {fmt(r, 'psnr_zoom1')} | "
                     f"{fmt(r, 'psnr_zoom2')} | {fmt(r, 'ssim', 4)} | {100 * r['coverage']:.2f} % | {fmt(r, 'ms', 3)} | "
                     f"{fmt(r, 'cpu_ms', 3)} | {irs(r)} | {yes(r['pareto'])} | {yes(r['pareto_ir'])} |")
        L.append("")
        L.append(f"### {m}: fraction bits F (fixed point, {dflt['splat']} splat, {dflt['fill']} fill)")
        L.append("")
        L.append("| depth | F | PSNR dB | SSIM | coverage diff | ms (wall) | CPU ms | Ir/frame | Pareto (CPU ms) | Pareto (Ir) |")
        L.append("|---:|---:|---:|---:|---:|---:|---:|---:|---|---|")
        for r in sorted(mo, key=lambda r: (r["depth"], r["frac"])):
            if (r["build"] != "fixed" or r["lod"] or r["depth"] not in (8, 10) or r["splat"] != dflt["splat"]
                    or r["fill"] != dflt["fill"]):
                continue
            L.append(f"| {r['depth']} | {r['frac']} | {r['psnr']:.3f} | {r['ssim']:.4f} | {100 * r['coverage']:.2f} % | "
                     f"{r['ms']:.3f} | {r['cpu_ms']:.3f} | {irs(r)} | {yes(r['pareto'])} | {yes(r['pareto_ir'])} |")
        lod_table(m, mo)
        bad = sorted({k[3] for k, st in status.items() if k[0] == m and st != "ok"})
        if bad:
            L.append("")
            L.append(f"F = {', '.join(map(str, bad))}: compiled, but not rendered at {a.size}: status "
                     + ", ".join(sorted({f'{st}' for k, st in status.items() if k[0] == m}))
                     + " (`size`: mc_octree_render refuses a target side above MC_TARGET_MAX = 2^(27 - F) pixels: "
                     "256 at F = 19, 8 at F = 24).")
        L.append("")
        front = sorted((r for r in mo if r["pareto"]), key=lambda r: r["cpu_ms"])
        L.append(f"Pareto front on CPU time ({len(front)} of {len(mo)} settings, fastest first): " + "; ".join(
            f"{label(r)} ({r['psnr']:.2f} dB, {r['cpu_ms']:.3f} ms)" for r in front) + ".")
        L.append("")
        front = sorted((r for r in mo if r["pareto_ir"]), key=lambda r: r["ir_per_frame"])
        L.append(f"Pareto front on instructions ({len(front)} of {len([r for r in mo if r['ir_per_frame'] != ''])} "
                 "counted settings, cheapest first): " + "; ".join(
            f"{label(r)} ({r['psnr']:.2f} dB, {r['ir_per_frame'] / 1e6:.2f} M Ir)" for r in front) + ".")
        L.append("")
        d = [r for r in mo if r["default"]]
        if d:
            r = d[0]
            L.append(f"Default (depth {r['depth']}, F {r['frac']}, {r['splat']} splat, {r['fill']} fill): "
                     f"{r['psnr']:.2f} dB, SSIM {r['ssim']:.4f}, {r['cpu_ms']:.3f} CPU ms/frame, {irs(r)} Ir/frame: "
                     + ("**on the Pareto front** (CPU time)" if r["pareto"] else
                        f"**not on the Pareto front** (CPU time; dominated by {r['dominated_by']})")
                     + (", " + ("**on**" if r["pareto_ir"] else "**not on**") + " the instruction-count front."
                        if r["pareto_ir"] != "" else "."))
            L.append("")
    # ---- both models: the default is one setting for every model ----------------------------------
    if len(models) > 1:
        both = []
        keys = {(r["depth"], r["build"], r["frac"], r["lod"], r["splat"], r["fill"]) for r in out}
        for k in sorted(keys):
            rs = [r for r in out if (r["depth"], r["build"], r["frac"], r["lod"], r["splat"], r["fill"]) == k]
            if len(rs) != len(models):
                continue
            b = dict(rs[0])
            b["model"] = "all"
            for f in ("psnr", "ssim", "cpu_ms", "ms"):
                b[f] = statistics.fmean(r[f] for r in rs)
            b["ir_per_frame"] = "" if any(r["ir_per_frame"] == "" for r in rs) else \
                round(statistics.fmean(r["ir_per_frame"] for r in rs))
            both.append(b)
        for r in both:
            r["pareto"] = int(not any(dominates(o, r) for o in both if o is not r))
            r["pareto_ir"] = "" if r["ir_per_frame"] == "" else int(
                not any(dominates(o, r, "ir_per_frame", 0.01) for o in both if o is not r))
        L.append(f"### Both models ({', '.join(models)}): means over the models")
        L.append("")
        L.append("The default is one setting for every model, so it is judged on the means over the models too. "
                 "Pareto front on instructions per frame (exact counts), cheapest first (F = 15, float and exact only; the other F "
                 "give the same PSNR within 0.01 dB and the same counts within 0.01 %; the level-selection bounds included):")
        L.append("")
        L.append("| setting | PSNR dB | SSIM | CPU ms | Ir/frame | Pareto (CPU ms) | Pareto (Ir) |")
        L.append("|---|---:|---:|---:|---:|---|---|")
        for r in sorted(both, key=lambda r: (r["ir_per_frame"] == "", r["ir_per_frame"] or 0)):
            if r["frac"] != 15 or not (r["pareto_ir"] or r["pareto"] or all(r[k] == dflt[k] for k in dflt)):
                continue
            L.append(f"| {label(r)}{' (default)' if all(r[k] == dflt[k] for k in dflt) else ''} | {r['psnr']:.2f} | "
                     f"{r['ssim']:.4f} | {r['cpu_ms']:.3f} | {irs(r)} | {yes(r['pareto'])} | {yes(r['pareto_ir'])} |")
        L.append("")
    L.append("### The default, and why")
    L.append("")
    L.append("@@CONCLUSION@@")
    L.append("")
    L.append(END)
    section = "\n".join(L) + "\n"
    # the interpretation is written by hand for the committed run (tests/accuracy/conclusion.md)
    concl = "tests/accuracy/conclusion.md"
    section = section.replace("@@CONCLUSION@@", open(concl).read().strip() if os.path.exists(concl) else
                              "(tests/accuracy/conclusion.md not written yet)")
    md = open(a.results_md).read() if os.path.exists(a.results_md) else ""
    old = re.search(re.escape(BEGIN) + r".*?" + re.escape(END) + r"\n?", md, re.S)
    if old:
        md = md[:old.start()] + section + md[old.end():]
    else:
        md = md.rstrip("\n") + "\n\n" + section
    open(a.results_md, "w").write(md)


if __name__ == "__main__":
    sys.exit(main())
