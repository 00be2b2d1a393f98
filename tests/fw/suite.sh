#!/usr/bin/env bash
# Firmware on Cortex-M under QEMU, for bunny00 on both boards (mps2-an386: Cortex-M4F,
# depth 8 at 320x240; lm3s6965evb: Cortex-M3 with 256 KiB flash and 64 KiB RAM, depth 7 at 160x128):
#   - make firmware builds it and its checks pass: no heap symbols, model arrays and frame buffers of
#     exactly budget.json's sizes, flash and RAM within the stated margins of budget.json's totals,
#     fits the board, static stack bound (-fstack-usage over the call graph) within the reservation
#     (runtime/front/fw/check_elf.py prints those lines; they are passed through here)
#   - the link refuses a heap call (same flags plus an object calling malloc), and the ELF-versus-budget
#     check fails when budget.json disagrees with the ELF
#   - make firmware-run: QEMU runs it to "done" with exit status 0; its frame checksum lines equal the
#     host viewer's --checksums lines for the same bake, byte for byte (the fixed-point runtime is
#     bit-exact across architectures), for the views of views.h and the frames with options of frames.h;
#     those take their paths: culling off skips no node where the default skipped some, the
#     level-of-detail bound draws a shallower level with fewer leaves, the magnified (squares) frame
#     draws the same leaves as at zoom 1 (wholly on screen); the frame it writes through semihosting equals the host's
#     --ppm output and converts to a valid PNG (build/tests/fw/BOARD.png)
#   - the measured stack high-water mark is below the static bound
# and for the same model baked with its mesh part on each board (make firmware FW_MESH=1: --as both at
# the board's mesh screen and --max-faces, boards/B.mk; lm3s6965evb: 128x96 and 2300 faces with the
# vertex cache, within 256 KiB flash and 64 KiB RAM; mps2-an386: the whole mesh at 320x240):
#   - the build's ELF checks pass, including the mesh part's RAM (ancestor map, facing bits, vertex
#     cache) at exactly budget.json's sizes; it is baked as the board asks
#   - under QEMU it prints, after the point frames, one "mesh frame" line per view
#     (runtime/front/common/mesh_frames.h: the three styles; the base, the full and middle levels),
#     every frame MC_OK, each line equal to the host viewer's --checksums line for the same bake, and
#     the point frames equal too; the run takes a few seconds (QEMU timeout 120 s)
#   - the measured stack high-water mark is below the static bound
# The toolchain comes from make deps: a missing tool is a failure, not a skip.
# Prints one line per check, "ok - NAME" or "not ok - NAME: why"; exits non-zero if any failed.
set -u
cd "$(dirname "$0")/../.." || exit 1
TAP_PREFIX="fw: "
. tests/lib.sh
# the firmware's compiles through the shared object cache (tests/cc_cached.sh): the runtime's
# objects are the same for a board's points, mesh and tracker firmware, and are compiled once
arm_cc="ARM_CC=tests/cc_cached.sh arm-none-eabi-gcc"
out=build/tests/fw
fresh_dir "$out"
check() { check_problems "$@"; }   # check NAME PROBLEMS
model=bunny00

# ---- the toolchain ----------------------------------------------------------------------------------
missing=""
for t in arm-none-eabi-gcc arm-none-eabi-nm arm-none-eabi-size arm-none-eabi-objdump qemu-system-arm python3; do
    command -v "$t" >/dev/null || missing="$missing $t"
done
[ -f /usr/lib/picolibc/arm-none-eabi/picolibc.specs ] || missing="$missing picolibc-arm-none-eabi"
check "toolchain installed (gcc-arm-none-eabi, picolibc-arm-none-eabi, qemu-system-arm)" \
    "${missing:+missing:$missing (run make deps)}"
[ -z "$missing" ] || exit 1

# ---- PPM to PNG, in Python's standard library ------------------------------------------------------
ppm2png() {   # ppm2png IN.ppm OUT.png: prints a problem, or nothing
    python3 - "$1" "$2" <<'EOF'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
parts = data.split(b"\n", 3)
if len(parts) != 4 or parts[0] != b"P6" or parts[2] != b"255":
    sys.exit("not a binary PPM with maxval 255")
w, h = map(int, parts[1].split())
pix = parts[3]
if len(pix) != w * h * 3:
    sys.exit(f"{len(pix)} pixel bytes for {w}x{h}")
raw = b"".join(b"\0" + pix[y * w * 3:(y + 1) * w * 3] for y in range(h))
chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) + \
      chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
open(sys.argv[2], "wb").write(png)
# read it back: signature, size, and the same pixels
back = open(sys.argv[2], "rb").read()
assert back[:8] == b"\x89PNG\r\n\x1a\n" and struct.unpack(">II", back[16:24]) == (w, h)
EOF
}

# the point frames: the views of views.h (default options), then frames.h's views with options
nviews=$(grep -c '^    {[^{]' runtime/front/common/views.h)
nframes=$((nviews + $(grep -c '^    {{' runtime/front/common/frames.h)))

option_paths() {   # option_paths FRAMES: what the frames with options (index >= nviews) fail to show, or nothing
    python3 - "$1" "$nviews" <<'EOF'
import re, sys
rows = {}
for line in open(sys.argv[1]):
    m = re.match(r"frame (\d+) yaw (-?\d+) pitch (-?\d+) roll (-?\d+) zoom (\d+) tx (-?\d+) ty (-?\d+) eye (\d+) "
                 r"error (\d+) cull (on|off) depth (\d+) level (\d+) size \S+ rc 0 points (\d+) culled (\d+) ", line)
    if m:
        g = m.groups()
        rows[int(g[0])] = dict(cam=g[1:8], zoom=int(g[4]), error=int(g[8]), cull=g[9], depth=int(g[10]),
                               level=int(g[11]), points=int(g[12]), culled=int(g[13]))
nviews = int(sys.argv[2])
why = []
opt = [i for i in sorted(rows) if i >= nviews]
if not opt: why.append("no frame with options")
for j in opt:
    r = rows[j]
    same = [i for i in sorted(rows) if i != j and rows[i]["cam"] == r["cam"]]
    if r["cull"] == "off":
        # culling off: no node skipped, more leaves than the same view culled
        p = [i for i in same if rows[i]["cull"] == "on" and rows[i]["error"] == r["error"]]
        if r["culled"] or not p or rows[p[0]]["culled"] == 0 or rows[p[0]]["points"] >= r["points"]:
            why.append(f"frame {j} (cull off) against {p[:1]}: culled {r['culled']}")
    elif r["error"]:
        # a level-of-detail bound: a shallower level than the same view at the depth asked, fewer leaves
        p = [i for i in same if rows[i]["error"] == 0 and rows[i]["cull"] == r["cull"]]
        if not p or r["level"] >= r["depth"] or rows[p[0]]["level"] != r["depth"] or r["points"] >= rows[p[0]]["points"]:
            why.append(f"frame {j} (error {r['error']}) level {r['level']} of {r['depth']} against {p[:1]}")
    elif r["zoom"] > 65536:
        # magnified (squares): wholly on screen, so the same leaves as the same view at zoom 1
        z = [i for i in rows if i != j and rows[i]["cam"][:3] == r["cam"][:3] and rows[i]["cam"][4:] == r["cam"][4:]
             and rows[i]["error"] == 0 and rows[i]["cull"] == "on" and rows[i]["zoom"] == 65536]
        if not z or rows[z[0]]["points"] != r["points"]:
            why.append(f"frame {j} (zoom {r['zoom']}) draws {r['points']} leaves, at zoom 1 {[rows[i]['points'] for i in z]}")
print("; ".join(why))
EOF
}

for b in mps2-an386 lm3s6965evb; do
    dir=build/fw/$b
    elf=$dir/$model.elf
    # ---- build and the post-link checks (a fresh link, so its memory usage table is printed) -------
    rm -f "$elf"
    make -s --no-print-directory "$arm_cc" firmware MODEL=$model BOARD=$b >"$out/$b.build.txt" 2>&1
    st=$?
    grep -E '^(ok|not ok) - fw: ' "$out/$b.build.txt" | sed "s/^\(ok\|not ok\) - fw: /\1 - fw: $b: /"
    grep -q '^not ok' "$out/$b.build.txt" && status=1
    if [ $st -ne 0 ] || [ ! -f "$elf" ]; then
        notok "$b: make firmware MODEL=$model BOARD=$b" "exit $st: $(grep -v '^ok' "$out/$b.build.txt" | tail -5 | oneline)"
        continue
    fi
    ok "$b: make firmware MODEL=$model BOARD=$b builds $elf"
    check "$b: link prints its memory usage (-Wl,--print-memory-usage)" \
        "$(grep -q 'Memory region' "$out/$b.build.txt" || echo 'no Memory region table in the build output')"

    # the bake the board asked for
    budget=$dir/$model/budget.json
    read -r depth screen < <(python3 -c 'import json,sys; b=json.load(open(sys.argv[1])); print(b["depth"], "%dx%d" % tuple(b["screen"]))' "$budget")
    want_depth=$(mkvar $b.depth)
    want_screen=$(mkvar $b.screen)
    check "$b: baked at the board's depth $want_depth and screen $want_screen" \
        "$([ "$depth $screen" = "$want_depth $want_screen" ] || echo "budget.json says depth $depth screen $screen")"
    if [ $b = lm3s6965evb ]; then
        # the issue's must-show: depth 7 at 160x128 or larger in 256 KiB flash and 64 KiB RAM
        w=${screen%x*} h=${screen#*x}
        check "$b: bunny00 depth 7 at 160x128 or larger fits 256 KiB flash and 64 KiB RAM" \
            "$([ "$depth" -ge 7 ] && [ "$w" -ge 160 ] && [ "$h" -ge 128 ] && grep -q "fits the board" "$out/$b.build.txt" && ! grep -q '^not ok.*fits the board' "$out/$b.build.txt" || echo "depth $depth screen $screen")"
    fi

    # ---- no heap, independently of check_elf.py ---------------------------------------------------
    bad=$(arm-none-eabi-nm "$elf" | awk '{print $NF}' |
        grep -E '^(malloc|calloc|realloc|free|_sbrk|sbrk|_malloc_r|_calloc_r|_realloc_r|_free_r|__wrap_.*|__real_.*)$' | oneline)
    check "$b: arm-none-eabi-nm shows no malloc, free, _sbrk, _malloc_r or __wrap_ symbol" "${bad:+found: $bad}"
    # the same link with one object that calls malloc must fail on the undefined __wrap_malloc
    cat >"$out/heap.c" <<'EOF'
#include <stdlib.h>
void *fw_heap_probe(unsigned n) { return malloc(n); }
int main(void) { return fw_heap_probe(4) != 0; }
EOF
    cflags=$(mkvar FW_CFLAGS BOARD=$b)
    ldflags=$(mkvar FW_LDFLAGS BOARD=$b | sed "s|-Wl,-Map=[^ ]*||")
    # shellcheck disable=SC2086
    arm-none-eabi-gcc $cflags -c -o "$out/heap.o" "$out/heap.c" 2>"$out/heap.txt" &&
        ! arm-none-eabi-gcc -o "$out/heap.elf" "$out/heap.o" $ldflags >>"$out/heap.txt" 2>&1
    r1=$?
    grep -q "undefined reference to \`__wrap_malloc'" "$out/heap.txt"
    r2=$?
    check "$b: the firmware link (--wrap=malloc,... without definitions) refuses a malloc call" \
        "$([ $r1 -eq 0 ] && [ $r2 -eq 0 ] || echo "$(oneline <"$out/heap.txt")")"

    # ---- the ELF-versus-budget check fails when budget.json disagrees -----------------------------
    python3 -c 'import json,sys; b=json.load(open(sys.argv[1])); [b["flash"].__setitem__(k, b["flash"][k] + 200000) for k in ("total", "image") if k in b["flash"]]; [b["ram"].__setitem__(k, b["ram"][k] - 4096) for k in ("total", "image") if k in b["ram"]]; json.dump(b, open(sys.argv[2], "w"))' \
        "$budget" "$out/$b.wrong-budget.json"
    python3 runtime/front/fw/check_elf.py --elf "$elf" --budget "$out/$b.wrong-budget.json" \
        --ld runtime/front/fw/boards/$b.ld --obj $dir/obj --depth "$depth" >"$out/$b.wrong.txt" 2>&1
    r=$?
    n=$(grep -c '^not ok.*budget.json' "$out/$b.wrong.txt")
    check "$b: check_elf.py fails when budget.json's flash and RAM totals disagree with the ELF" \
        "$([ $r -ne 0 ] && [ "$n" -eq 2 ] || echo "exit $r, $n failing budget lines: $(oneline <"$out/$b.wrong.txt")")"

    # ---- run under QEMU, compare with the host ---------------------------------------------------
    make -s --no-print-directory "$arm_cc" firmware-run MODEL=$model BOARD=$b FW_QEMU_TIMEOUT=300 >"$out/$b.run.txt" 2>&1
    st=$?
    run=$dir/$model.run.txt
    check "$b: make firmware-run: QEMU runs the firmware to \"done\", exit status 0" \
        "$([ $st -eq 0 ] && grep -q '^done' "$run" 2>/dev/null || echo "exit $st: $(tail -5 "$out/$b.run.txt" | oneline)")"
    grep '^frame ' "$run" >"$out/$b.fw-frames.txt" 2>/dev/null
    $dir/$model/$model-view --checksums --ppm "$out/$b.host.ppm" >"$out/$b.host-frames.txt" 2>"$out/$b.host-err.txt"
    hst=$?
    nfw=$(wc -l <"$out/$b.fw-frames.txt")
    check "$b: the host viewer's --checksums renders the same $nframes frames ($nviews views, $((nframes - nviews)) with options) (exit 0)" \
        "$([ $hst -eq 0 ] && [ "$(wc -l <"$out/$b.host-frames.txt")" -eq "$nframes" ] || echo "exit $hst, $(wc -l <"$out/$b.host-frames.txt") lines")"
    check "$b: firmware prints $nframes frame checksum lines, every render MC_OK" \
        "$([ "$nfw" -eq "$nframes" ] && ! grep -qv ' rc 0 ' "$out/$b.fw-frames.txt" || echo "$nfw lines: $(head -3 "$out/$b.fw-frames.txt" | oneline)")"
    check "$b: frame checksums (FNV-1a of colour and depth buffers) equal the host's, all $nframes frames" \
        "$(cmp -s "$out/$b.fw-frames.txt" "$out/$b.host-frames.txt" || diff "$out/$b.fw-frames.txt" "$out/$b.host-frames.txt" | head -4 | oneline)"
    check "$b: the frames with options take their paths: culling skips nodes by default and none when off, the level of detail draws a shallower level, the squares frame the same leaves as at zoom 1" \
        "$(option_paths "$out/$b.fw-frames.txt")"
    check "$b: the frame written through semihosting equals the host's --ppm, byte for byte" \
        "$(cmp "$dir/$model.ppm" "$out/$b.host.ppm" 2>&1 | oneline)"
    problem=$(ppm2png "$dir/$model.ppm" "$out/$b.png" 2>&1 | tail -1)
    check "$b: the semihosted frame converts to a valid PNG ($out/$b.png)" "$problem"

    # ---- measured stack against the static bound --------------------------------------------------
    used=$(sed -n 's/^stack used \([0-9]*\) of.*/\1/p' "$run")
    bound=$(sed -n 's/^# .*stack bound \([0-9]*\) bytes.*/\1/p' "$out/$b.build.txt" | head -1)
    check "$b: measured stack high-water mark (${used:-?} bytes) is within the static bound (${bound:-?} bytes)" \
        "$([ -n "$used" ] && [ -n "$bound" ] && [ "$used" -gt 0 ] && [ "$used" -le "$bound" ] || echo "used '${used}' bound '${bound}'")"
done

# ---- the mesh part (FW_MESH=1) on both boards ----------------------------------------------------
mesh_schedule() {   # mesh_schedule FILE: what the "mesh frame" lines in FILE leave out, or nothing
    python3 - "$1" <<'EOF'
import re, sys
rows = [re.match(r"mesh frame (\d+) style (\S+) level (\d+) of (\d+) faces (\d+) of (\d+) .* drawn (\d+) .*line-pixels (\d+) ", l)
        for l in open(sys.argv[1])]
rows = [r.groups() for r in rows if r]
styles = ("shaded", "lines", "shaded+lines")
levels = {int(r[2]) for r in rows}
why = []
if {r[1] for r in rows} != set(styles): why.append(f"styles {sorted({r[1] for r in rows})}")
if not rows or int(rows[0][3]) not in levels: why.append("no frame at the full level")
if len(levels) < 5: why.append(f"only {len(levels)} levels")
# (the lines style draws no face: its faces only hide line pixels, mesh_frame.h)
if any(int(r[6]) == 0 for r in rows if r[1] != "lines"): why.append("a frame drew no face")
if any(int(r[7]) == 0 for r in rows if r[1] != "shaded"): why.append("a frame with lines drew no line pixel")
why += [f"{s} at one level only" for s in styles if len({r[2] for r in rows if r[1] == s}) < 2]
print("; ".join(why))
EOF
}

for b in mps2-an386 lm3s6965evb; do
    dir=build/fw/$b-mesh
    elf=$dir/$model.elf
    t=$b-mesh
    rm -f "$elf"
    make -s --no-print-directory "$arm_cc" firmware MODEL=$model BOARD=$b FW_MESH=1 >"$out/$t.build.txt" 2>&1
    st=$?
    grep -E '^(ok|not ok) - fw: ' "$out/$t.build.txt" | sed "s/^\(ok\|not ok\) - fw: /\1 - fw: $b mesh: /"
    grep -q '^not ok' "$out/$t.build.txt" && status=1
    if [ $st -ne 0 ] || [ ! -f "$elf" ]; then
        notok "$b mesh: make firmware MODEL=$model BOARD=$b FW_MESH=1" "exit $st: $(grep -v '^ok' "$out/$t.build.txt" | tail -5 | oneline)"
        continue
    fi
    ok "$b mesh: make firmware MODEL=$model BOARD=$b FW_MESH=1 builds $elf"
    check "$b mesh: the ELF checks include the mesh part's RAM (ancestor map, facing bits, vertex cache)" \
        "$(grep -q "^ok - fw: .*mesh part's RAM" "$out/$t.build.txt" || echo 'no passing mesh RAM line in the build output')"

    budget=$dir/$model/budget.json
    want_depth=$(mkvar FW_DEPTH BOARD=$b FW_MESH=1)
    want_screen=$(mkvar FW_SCREEN BOARD=$b FW_MESH=1)
    want_faces=$(mkvar FW_MESH_FACES BOARD=$b FW_MESH=1)
    want_faces=${want_faces:-0}
    read -r depth screen faces capped flash ram < <(python3 -c 'import json,sys; b=json.load(open(sys.argv[1])); p=b.get("pmesh", {}); print(b["depth"], "%dx%d" % tuple(b["screen"]), p.get("faces", 0), p.get("input", {}).get("collapses_applied_for_max_faces", 0), b["flash"]["image"], b["ram"]["image"])' "$budget")
    check "$b mesh: baked with its mesh part as the board asks: depth $want_depth, screen $want_screen, faces $want_faces (0: all)" \
        "$([ "$depth $screen" = "$want_depth $want_screen" ] && [ "${faces:-0}" -gt 0 ] &&
            { { [ "$want_faces" = 0 ] && [ "$capped" = 0 ]; } || [ "$faces" -le "$want_faces" ]; } ||
            echo "budget.json says depth $depth screen $screen faces $faces (collapses for --max-faces: $capped)")"
    if [ $b = lm3s6965evb ]; then
        check "$b mesh: $faces faces with the vertex cache at $screen fit 256 KiB flash and 64 KiB RAM (budget.json image: flash $flash, RAM $ram)" \
            "$(grep -q '^ok - fw: .*fits the board' "$out/$t.build.txt" && [ "$flash" -le 262144 ] && [ "$ram" -le 65536 ] ||
                grep 'fits the board' "$out/$t.build.txt" | oneline)"
    fi

    # ---- run under QEMU, compare with the host ---------------------------------------------------
    start=$(date +%s)
    make -s --no-print-directory "$arm_cc" firmware-run MODEL=$model BOARD=$b FW_MESH=1 FW_QEMU_TIMEOUT=120 >"$out/$t.run.txt" 2>&1
    st=$?
    secs=$(($(date +%s) - start))
    run=$dir/$model.run.txt
    check "$b mesh: make firmware-run FW_MESH=1: QEMU runs the firmware to \"done\", exit status 0 (${secs} s with the host viewer's link)" \
        "$([ $st -eq 0 ] && grep -q '^done' "$run" 2>/dev/null || echo "exit $st: $(tail -5 "$out/$t.run.txt" | oneline)")"
    grep '^frame ' "$run" >"$out/$t.fw-frames.txt" 2>/dev/null
    grep '^mesh frame ' "$run" >"$out/$t.fw-mesh.txt" 2>/dev/null
    $dir/$model/$model-view --checksums >"$out/$t.host.txt" 2>"$out/$t.host-err.txt"
    hst=$?
    grep '^frame ' "$out/$t.host.txt" >"$out/$t.host-frames.txt"
    grep '^mesh frame ' "$out/$t.host.txt" >"$out/$t.host-mesh.txt"
    check "$b mesh: the host viewer's --checksums prints $nframes point and then $nviews mesh frame lines (exit 0)" \
        "$([ $hst -eq 0 ] && [ "$(wc -l <"$out/$t.host-frames.txt")" -eq "$nframes" ] &&
            [ "$(wc -l <"$out/$t.host-mesh.txt")" -eq "$nviews" ] && [ "$(wc -l <"$out/$t.host.txt")" -eq $((nframes + nviews)) ] &&
            [ "$(head -1 "$out/$t.host-mesh.txt")" = "$(sed -n "$((nframes + 1))p" "$out/$t.host.txt")" ] ||
            echo "exit $hst, $(wc -l <"$out/$t.host.txt") lines")"
    nfw=$(wc -l <"$out/$t.fw-mesh.txt")
    first_mesh=$(grep -n '^mesh frame ' "$run" | head -1 | cut -d: -f1)
    last_point=$(grep -n '^frame ' "$run" | tail -1 | cut -d: -f1)
    check "$b mesh: firmware prints $nviews mesh frame lines after the point frames, every frame MC_OK" \
        "$([ "$nfw" -eq "$nviews" ] && ! grep -qv ' rc 0 ' "$out/$t.fw-mesh.txt" &&
            [ "${first_mesh:-0}" -gt "${last_point:-0}" ] || echo "$nfw lines: $(head -3 "$out/$t.fw-mesh.txt" | oneline)")"
    check "$b mesh: the frames draw the three styles, each at two levels or more, the full level and five levels in all" \
        "$(mesh_schedule "$out/$t.fw-mesh.txt")"
    # the level's neighbour table where the board's bake asks for one (boards/B.mk mesh_opts)
    want_nbr=no
    [[ " $(mkvar FW_BAKE_OPTS BOARD=$b FW_MESH=1 MODEL=$model) " == *" --mesh-neighbours "* ]] && want_nbr=yes
    check "$b mesh: the firmware keeps a neighbour table as its bake asks ($want_nbr)" \
        "$(grep -q "^modelc firmware: mesh .* neighbour table $want_nbr\$" "$run" || grep '^modelc firmware: mesh' "$run" | oneline)"
    base=$(sed -n 's/^modelc firmware: mesh .* (base \([0-9]*\), .*/\1/p' "$run")
    check "$b mesh: a frame draws the base level (${base:-?} vertices)" \
        "$([ -n "$base" ] && grep -q " level $base of " "$out/$t.fw-mesh.txt" || echo "no frame at level '$base'")"
    check "$b mesh: mesh frame checksum lines (style, level, faces drawn, FNV-1a) equal the host's, all $nviews views" \
        "$([ "$nfw" -gt 0 ] && cmp -s "$out/$t.fw-mesh.txt" "$out/$t.host-mesh.txt" ||
            diff "$out/$t.fw-mesh.txt" "$out/$t.host-mesh.txt" | head -4 | oneline)"
    check "$b mesh: point frame checksums of the mesh bake equal the host's, all $nframes frames" \
        "$([ "$(wc -l <"$out/$t.fw-frames.txt")" -eq "$nframes" ] && cmp -s "$out/$t.fw-frames.txt" "$out/$t.host-frames.txt" ||
            diff "$out/$t.fw-frames.txt" "$out/$t.host-frames.txt" | head -4 | oneline)"
    used=$(sed -n 's/^stack used \([0-9]*\) of.*/\1/p' "$run")
    bound=$(sed -n 's/^# .*stack bound \([0-9]*\) bytes.*/\1/p' "$out/$t.build.txt" | head -1)
    check "$b mesh: measured stack high-water mark (${used:-?} bytes) is within the static bound (${bound:-?} bytes)" \
        "$([ -n "$used" ] && [ -n "$bound" ] && [ "$used" -gt 0 ] && [ "$used" -le "$bound" ] || echo "used '${used}' bound '${bound}'")"
done
exit $status
