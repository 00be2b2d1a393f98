#!/usr/bin/env bash
# The host viewers build/NAME/NAME-view of every catalogue model, as binaries:
#   - no heap: no allocator symbol in nm or nm -D, no __wrap_/__real_ symbol; and, once, proof that
#     the Makefile's link (--wrap=malloc,...) fails for an object that calls the heap
#   - --png writes a valid PNG (signature, IHDR size, chunk CRCs, image data) with the same pixels as
#     --ppm, which writes a valid P6 of the requested --size
#   - bad options: one error line on stderr, nothing on stdout, exit status 2
#   - no files read at run time (strace): only shared libraries / locale data, and the output file
# then tests/host/interactive.sh (the terminal mode), passed through.
# Prints one line per check, "ok - NAME" or "not ok - NAME: why"; exits non-zero if any failed.
set -u
cd "$(dirname "$0")/../.." || exit 1
TAP_PREFIX="host: "
. tests/lib.sh
out=build/tests/host
fresh_dir "$out"
check() { check_problems "$@"; }   # check NAME PROBLEMS

# Makefile variables (mkvar) are read from the Makefile itself so the re-link below is the real one
models=$(mkvar CATALOGUE)
[ -n "$models" ] || { notok "catalogue" "cannot read CATALOGUE from the Makefile"; exit 1; }

# ---- (a) no heap symbols ------------------------------------------------------------------------
heap_syms='malloc calloc realloc reallocarray free sbrk brk aligned_alloc posix_memalign memalign valloc pvalloc strdup strndup asprintf vasprintf getline getdelim open_memstream'
heap_re="^($(echo "$heap_syms" | tr ' ' '|'))(@.*)?$"
heap_check() {   # prints the offending symbols of binary $1
    { nm "$1" 2>/dev/null; nm -D "$1" 2>/dev/null; } | awk 'NF >= 2 {print $NF}' | sort -u |
        grep -E "$heap_re|^__(wrap|real)_" | tr '\n' ' '
}

viewers=()
for m in $models; do
    v=build/$m/$m-view
    if [ ! -x "$v" ]; then
        notok "$m: viewer" "$v missing (run make views)"
        continue
    fi
    viewers+=("$m")
    syms=$(nm "$v" 2>&1 | wc -l)
    if [ "$syms" -lt 10 ]; then
        notok "$m: no heap symbols (nm, nm -D)" "nm lists only $syms lines: stripped binary?"
        continue
    fi
    bad=$(heap_check "$v")
    check "$m: no heap symbols in nm or nm -D ($heap_syms; no __wrap_/__real_)" "${bad:+found: $bad}"
done

# ---- (b) the --wrap link refuses heap calls ----------------------------------------------------
# Re-links the first viewer exactly as the Makefile does: without extra objects it must link (so the
# failure below is the heap call's, not the command's); with one object calling the heap it must fail
# on the undefined __wrap_ symbols. The self-test also checks heap_check itself flags a heap symbol.
if [ ${#viewers[@]} -gt 0 ]; then
    m=${viewers[0]}
    rl=$out/relink
    mkdir -p "$rl"
    cc=$(mkvar CC)
    cflags="$(mkvar CFLAGS) $(mkvar RT_CFLAGS) -ffunction-sections -fdata-sections"
    ldflags=$(mkvar VIEW_LDFLAGS)
    rtobj=$(mkvar RT_OBJ)
    hostobj=$(mkvar HOST_OBJ)
    cat >"$rl/heap.c" <<'EOF'
/* tests/host/suite.sh: a constructor (kept by --gc-sections) that uses the heap */
#include <stdlib.h>
void *volatile mc_test_sink;   /* the pointers escape, so the compiler cannot drop the calls */
__attribute__((constructor)) static void mc_test_uses_heap(void)
{
    mc_test_sink = malloc(16);
    mc_test_sink = realloc(mc_test_sink, 32);
    free(mc_test_sink);
    mc_test_sink = calloc(1, 8);
    free(mc_test_sink);
}
EOF
    problems=""
    objs=()
    for f in build/"$m"/*.c; do
        o="$rl/$(basename "$f" .c).o"
        # shellcheck disable=SC2086
        $cc $cflags -c -o "$o" "$f" 2>>"$rl/compile.log" || problems+="cannot compile $f; "
        objs+=("$o")
    done
    # shellcheck disable=SC2046,SC2086
    $cc $(mkvar CFLAGS) -std=c99 -c -o "$rl/heap.o" "$rl/heap.c" 2>>"$rl/compile.log" || problems+="cannot compile heap.c; "
    if [ -n "$problems" ]; then
        notok "$m: re-link with the Makefile's --wrap flags" "$problems$(head -n 3 "$rl/compile.log" | oneline)"
    else
        # shellcheck disable=SC2086
        if $cc $cflags -o "$rl/$m-view" "${objs[@]}" $rtobj $hostobj $ldflags >"$rl/link.log" 2>&1; then
            ok "$m: re-link with the Makefile's flags ($ldflags) succeeds"
        else
            notok "$m: re-link with the Makefile's flags ($ldflags) succeeds" "$(head -n 3 "$rl/link.log" | oneline)"
        fi
        # shellcheck disable=SC2086
        if $cc $cflags -o "$rl/$m-heap-view" "${objs[@]}" "$rl/heap.o" $rtobj $hostobj $ldflags >"$rl/link-heap.log" 2>&1; then
            notok "$m: linking an object that calls malloc/calloc/realloc/free fails" \
                "the link succeeded: the --wrap flags do not catch heap calls"
        else
            missing=""
            for s in malloc calloc realloc free; do
                grep -q "undefined reference to \`__wrap_$s'" "$rl/link-heap.log" || missing+="__wrap_$s "
            done
            check "$m: linking an object that calls malloc/calloc/realloc/free fails on undefined __wrap_*" \
                "${missing:+the link failed but without an undefined reference to: $missing($(head -n 2 "$rl/link-heap.log" | oneline))}"
        fi
        # the nm check sees heap symbols when they are there: the same object linked without --wrap
        # shellcheck disable=SC2086
        if $cc $cflags -o "$rl/$m-heap-nowrap" "${objs[@]}" "$rl/heap.o" $rtobj $hostobj -Wl,--gc-sections -lm \
            >"$rl/link-nowrap.log" 2>&1; then
            bad=$(heap_check "$rl/$m-heap-nowrap")
            case " $bad " in
                *" malloc"*) ok "$m: the nm heap check flags a binary that calls malloc (self-test)" ;;
                *) notok "$m: the nm heap check flags a binary that calls malloc (self-test)" "nm found only: $bad" ;;
            esac
        else
            notok "$m: the nm heap check flags a binary that calls malloc (self-test)" "$(head -n 2 "$rl/link-nowrap.log" | oneline)"
        fi
    fi
fi

# ---- (c) image files ---------------------------------------------------------------------------
# check_ppm FILE W H: prints problems; also fails an image that is all background
check_ppm() {
    local f=$1 w=$2 h=$3 header size want
    [ -s "$f" ] || { echo "no file written"; return; }
    header=$(head -c 64 "$f" | head -n 3 | tr '\n' '|')
    [ "$header" = "P6|$w $h|255|" ] || { echo "header '$header', want 'P6|$w $h|255|'"; return; }
    size=$(stat -c %s "$f")
    want=$((${#w} + ${#h} + 9 + w * h * 3))   # "P6\n", "W H\n", "255\n", then the pixels
    [ "$size" -eq "$want" ] || { echo "$size bytes, want $want"; return; }
    # at least one pixel is not the background (24, 24, 32): the model was drawn
    if ! tail -c $((w * h * 3)) "$f" | od -An -v -tu1 -w3 | grep -qv '^ *24 *24 *32$'; then
        echo "every pixel is background"
    fi
}

# check_png FILE W H [PPM]: signature and IHDR in shell; then with python3 (make deps: missing is a
# failure), every chunk's CRC and the image data's inflated size; and (given a PPM of the same view)
# the same pixels, decoded by libpng (pngtopnm)
check_png() {
    local f=$1 w=$2 h=$3 ppm=${4:-} sig ihdr
    [ -s "$f" ] || { echo "no file written"; return; }
    sig=$(head -c 8 "$f" | od -An -tx1 | tr -d ' \n')
    [ "$sig" = 89504e470d0a1a0a ] || { echo "signature $sig"; return; }
    ihdr=$(head -c 24 "$f" | tail -c 16 | od -An -tx1 | tr -d ' \n')
    [ "${ihdr:0:16}" = 0000000d49484452 ] || { echo "first chunk is not a 13-byte IHDR: $ihdr"; return; }
    [ $((16#${ihdr:16:8})) -eq "$w" ] && [ $((16#${ihdr:24:8})) -eq "$h" ] ||
        { echo "IHDR says $((16#${ihdr:16:8}))x$((16#${ihdr:24:8})), want ${w}x$h"; return; }
    command -v python3 >/dev/null || { echo "python3 missing (make deps): chunks and pixels not checked"; return; }
    python3 - "$f" "$w" "$h" "$ppm" <<'EOF'
import struct, sys, zlib
path, w, h, ppm = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
data = open(path, 'rb').read()
pos, idat, chunks = 8, b'', []
while pos < len(data):
    if pos + 12 > len(data): sys.exit(print('truncated chunk at byte %d' % pos))
    n, kind = struct.unpack('>I4s', data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + n]
    crc, = struct.unpack('>I', data[pos + 8 + n:pos + 12 + n])
    if zlib.crc32(kind + body) & 0xffffffff != crc: sys.exit(print('bad CRC in %s chunk' % kind.decode('latin1')))
    chunks.append(kind)
    if kind == b'IHDR':
        _, _, depth, ctype, comp, filt, inter = struct.unpack('>IIBBBBB', body)
        if (depth, ctype, comp, filt, inter) != (8, 2, 0, 0, 0):
            sys.exit(print('IHDR: bit depth %d colour type %d (want 8-bit RGB, not interlaced)' % (depth, ctype)))
    if kind == b'IDAT': idat += body
    pos += 12 + n
if chunks[-1:] != [b'IEND']: sys.exit(print('no IEND at the end'))
raw = zlib.decompress(idat)
if len(raw) != h * (3 * w + 1): sys.exit(print('image data %d bytes, want %d' % (len(raw), h * (3 * w + 1))))
EOF
    # the pixels, unfiltered by another decoder (libpng's, through netpbm's pngtopnm), against the PPM
    [ -z "$ppm" ] && return
    command -v pngtopnm >/dev/null || { echo "pngtopnm missing (make deps: netpbm)"; return; }
    cmp -s <(pngtopnm "$f" 2>/dev/null | tail -c $((w * h * 3))) <(tail -c $((w * h * 3)) "$ppm") ||
        echo "pixels differ from the PPM of the same view (decoded by pngtopnm)"
}

# run_viewer LOG VIEWER ARGS...: runs with a time limit, stdout and stderr to LOG.out and LOG.err
run_viewer() {
    local log=$1
    shift
    timeout 60 "$@" >"$log.out" 2>"$log.err" </dev/null
}

for m in "${viewers[@]}"; do
    v=build/$m/$m-view
    d=$out/$m
    mkdir -p "$d"
    maxsize=$("$v" --help 2>/dev/null | sed -n 's/.*frame size, at most \([0-9]*x[0-9]*\).*/\1/p')
    [ -n "$maxsize" ] || maxsize=320x240
    maxw=${maxsize%x*}
    maxh=${maxsize#*x}
    # the default frame
    if run_viewer "$d/default" "$v" --ppm "$d/default.ppm"; then
        check "$m: --ppm writes a P6 of the default size 320x240" "$(check_ppm "$d/default.ppm" 320 240)"
    else
        notok "$m: --ppm writes a P6 of the default size 320x240" "exit status $?: $(oneline <"$d/default.err")"
    fi
    # requested sizes, one turned view each; the PNG of the same view has the same pixels
    for size in 160x120 "${maxw}x$maxh" 97x61 1x1; do
        w=${size%x*}
        h=${size#*x}
        args=(--size "$size" --yaw 30 --pitch -20 --roll 5)
        [ "$size" = 1x1 ] && args=(--size 1x1)   # the centre pixel of the frontal view: the model
        if run_viewer "$d/ppm-$size" "$v" "${args[@]}" --ppm "$d/$size.ppm"; then
            check "$m: --ppm --size $size writes a ${w}x$h P6" "$(check_ppm "$d/$size.ppm" "$w" "$h")"
        else
            notok "$m: --ppm --size $size writes a ${w}x$h P6" "exit status $?: $(oneline <"$d/ppm-$size.err")"
        fi
        if run_viewer "$d/png-$size" "$v" "${args[@]}" --png "$d/$size.png"; then
            check "$m: --png --size $size writes a valid ${w}x$h PNG with the PPM's pixels" \
                "$(check_png "$d/$size.png" "$w" "$h" "$d/$size.ppm" | oneline)"
        else
            notok "$m: --png --size $size writes a valid ${w}x$h PNG with the PPM's pixels" \
                "exit status $?: $(oneline <"$d/png-$size.err")"
        fi
    done

    # level of detail (--error, default one pixel): a zoomed-out view draws the shallower level the
    # renderer picks, and that frame is the one --error 0 --depth draws at that level
    lod_why=""
    if run_viewer "$d/lod" "$v" --zoom 0.25 --yaw 20 --png "$d/lod.png" &&
        run_viewer "$d/lod-full" "$v" --zoom 0.25 --yaw 20 --error 0 --png "$d/lod-full.png"; then
        ld=$(sed -nE 's/.* depth ([0-9]+) .*/\1/p' "$d/lod.out")
        fd=$(sed -nE 's/.* depth ([0-9]+) .*/\1/p' "$d/lod-full.out")
        if [ -z "$ld" ] || [ -z "$fd" ] || { [ "$ld" -ge "$fd" ] && [ "$fd" -gt 1 ]; }; then
            lod_why="zoom 0.25 drew depth '$ld', --error 0 depth '$fd'"
        elif ! run_viewer "$d/lod-exact" "$v" --zoom 0.25 --yaw 20 --error 0 --depth "$ld" --png "$d/lod-exact.png"; then
            lod_why="--depth $ld: $(oneline <"$d/lod-exact.err")"
        elif ! cmp -s "$d/lod.png" "$d/lod-exact.png"; then
            lod_why="the frame differs from --error 0 --depth $ld's"
        fi
    else
        lod_why="exit status $?: $(cat "$d/lod.err" "$d/lod-full.err" | oneline)"
    fi
    check "$m: at zoom 0.25 the level of detail draws a shallower level, the same frame as --depth at it" "$lod_why"

    # back-facing subtrees (--cull, on by default where the bake has normal cones: closed meshes):
    # skipped nodes only where cones were made; without hole filling, the frame changes where the far
    # side showed through gaps of the front surface (background with culling) and, at most 0.2 % of
    # the model's pixels, where a back cell's centre lay nearer than the front cell's (the surfaces
    # within a leaf of each other: a leaf is drawn at its cell's centre, not on the surface)
    made=$(python3 -c 'import json,sys; print(int(json.load(open(sys.argv[1])).get("cones", {}).get("made", False)))' \
        "build/$m/budget.json" 2>/dev/null)
    cull_why=""
    skipped=$("$v" --bench 3 --yaw 40 2>/dev/null | sed -n 's/^back-facing nodes skipped per frame: //p')
    if [ -z "$made" ] || [ -z "$skipped" ]; then
        cull_why="no cones entry in budget.json ('$made') or no skipped count from --bench ('$skipped')"
    elif { [ "$made" = 1 ] && [ "$skipped" = 0 ]; } || { [ "$made" = 0 ] && [ "$skipped" != 0 ]; }; then
        cull_why="cones made: $made, nodes skipped per frame: $skipped"
    else
        for view in "--yaw 40 --pitch 20" "--yaw 200 --pitch -30 --zoom 1.5"; do
            # shellcheck disable=SC2086
            if run_viewer "$d/cull-on" "$v" $view --no-finish --ppm "$d/cull-on.ppm" &&
                run_viewer "$d/cull-off" "$v" $view --no-finish --cull off --ppm "$d/cull-off.ppm"; then
                cull_why+=$(python3 - "$d/cull-on.ppm" "$d/cull-off.ppm" "$view" <<'PY'
import sys
def px(f):
    b = open(f, "rb").read()
    hdr = b.split(b"\n", 3)
    return hdr[3]
a, b = px(sys.argv[1]), px(sys.argv[2])
bg = bytes((24, 24, 32))
model = sum(1 for i in range(0, len(b), 3) if b[i:i + 3] != bg)
diff = [i for i in range(0, len(b), 3) if a[i:i + 3] != b[i:i + 3]]
gaps = sum(1 for i in diff if a[i:i + 3] == bg)
print("# %s: %d of %d model pixels differ, %d of them gaps" % (sys.argv[3], len(diff), model, gaps), file=sys.stderr)
if not model or (len(diff) - gaps) * 500 > model:
    print("%s: %d of %d model pixels differ, %d not gaps; " % (sys.argv[3], len(diff), model, len(diff) - gaps))
PY
                )
            else
                cull_why+="$view: exit status $?: $(cat "$d/cull-on.err" "$d/cull-off.err" | oneline); "
            fi
        done
    fi
    check "$m: --cull skips back-facing nodes only where the bake has cones (made: ${made:-?}); the frame changes at gaps and under 0.2 % elsewhere" "$cull_why"

    # ---- (d) bad options: one line on stderr, nothing on stdout, status 2 -------------------------
    bad_cases=(
        "--bogus" "--zoom 1000" "--depth 99" "--size 99999x1" "--size $((maxw + 1))x$maxh"
        "--size 0x10" "--size 10" "--zoom abc" "--zoom 0" "--depth 0" "--depth 1.5" "--yaw x"
        "--bench 0" "--png" "stray-argument" "--ppm /nonexistent-dir/x.ppm" "--png /nonexistent-dir/x.png"
        "--error 65" "--error 0.01" "--error -1" "--error px" "--cull maybe"
    )
    problems=""
    for c in "${bad_cases[@]}"; do
        # shellcheck disable=SC2086
        (cd "$d" && exec timeout 60 "$OLDPWD/$v" $c >bad.out 2>bad.err </dev/null)
        rc=$?
        lines=$(wc -l <"$d/bad.err")
        if [ "$rc" -ne 2 ] || [ "$lines" -ne 1 ] || [ -s "$d/bad.out" ]; then
            problems+="'$c': status $rc, $lines stderr lines ($(head -c 160 "$d/bad.err" | oneline)), $(wc -c <"$d/bad.out") bytes on stdout; "
        fi
    done
    check "$m: ${#bad_cases[@]} bad option sets each give one error line and status 2" "$problems"
    # no terminal and no output option: an error, not a hang
    (exec timeout 20 "$v" >"$d/notty.out" 2>"$d/notty.err" </dev/null)
    rc=$?
    [ "$rc" -eq 2 ] && [ "$(wc -l <"$d/notty.err")" -eq 1 ] && problems="" ||
        problems="status $rc, $(wc -l <"$d/notty.err") stderr lines"
    check "$m: no output option and stdout not a terminal: one error line, status 2" "$problems"
    if run_viewer "$d/help" "$v" --help && grep -q '^usage:' "$d/help.out" && [ ! -s "$d/help.err" ]; then
        ok "$m: --help prints the usage on stdout, status 0"
    else
        notok "$m: --help prints the usage on stdout, status 0" "status $?, $(head -c 100 "$d/help.err" | oneline)"
    fi

    # ---- (e) no files read at run time ----------------------------------------------------------
    name="$m: reads no files at run time (strace: only shared libraries, locale data, the --ppm output)"
    if ! command -v strace >/dev/null; then
        notok "$name" "strace not installed (apt-get install strace)"
        continue
    fi
    abs_out=$PWD/$d/traced.ppm
    (cd "$d" && exec timeout 60 strace -f -qq -e trace=open,openat,openat2,creat,execve -o strace.log \
        "$OLDPWD/$v" --ppm traced.ppm --yaw 45 >/dev/null 2>strace.err </dev/null)
    rc=$?
    if [ "$rc" -ne 0 ] || [ ! -s "$d/strace.log" ]; then
        notok "$name" "strace run failed (status $rc): $(head -n 2 "$d/strace.err" | oneline)"
        continue
    fi
    problems=""
    opened_output=0
    while IFS= read -r line; do
        case $line in *execve\(*) continue ;; esac
        path=$(echo "$line" | sed -nE 's/.*open(at2?)?\((AT_FDCWD, )?"([^"]*)".*/\3/p; s/.*creat\("([^"]*)".*/\1/p')
        [ -n "$path" ] || continue
        case $path in
            traced.ppm | "$abs_out")
                opened_output=1
                echo "$line" | grep -qE 'O_WRONLY|O_RDWR|creat\(' || problems+="output opened without writing: $line; " ;;
            /etc/ld.so.cache | /etc/ld.so.preload | /usr/lib/locale/* | /usr/share/locale/* | /usr/lib/*/gconv/*) ;;
            /lib/* | /lib64/* | /usr/lib/* | /usr/lib64/* | /usr/local/lib/*)
                case ${path##*/} in
                    *.so | *.so.* | glibc-hwcaps | tls | haswell | x86_64 | avx512_1 | x86-64-v[234]) ;;
                    *) problems+="$path; " ;;
                esac ;;
            *) problems+="$path; " ;;
        esac
    done <"$d/strace.log"
    [ "$opened_output" = 1 ] || problems+="the output file was never opened (trace: $(head -n 5 "$d/strace.log" | oneline)); "
    check "$name" "${problems:+opened: $problems}"
done

# ---- interactive mode (tests/host/interactive.sh) -------------------------------------------------
if [ ! -x tests/host/interactive.sh ]; then
    notok "interactive.sh" "tests/host/interactive.sh missing or not executable"
else
    tests/host/interactive.sh >"$out/interactive.log" 2>&1
    rc=$?
    grep -E '^(ok|not ok) ' "$out/interactive.log" | sed -E 's/^(ok|not ok) - /\1 - host: /'
    if [ "$rc" -ne 0 ]; then
        status=1
        grep -q '^not ok ' "$out/interactive.log" ||
            notok "interactive.sh" "exited with status $rc without reporting a failure: $(tail -n 3 "$out/interactive.log" | oneline)"
    fi
fi

exit $status
