#!/usr/bin/env bash
# Unit tests of the runtime: fixed point, sine table and rotation, bits, rng and chunk cursors, the
# progressive mesh's level of detail (pmesh), a face's shade and crease bits (mesh face) and the host viewer's automatic choice of it (lod auto),
# clipped lines (line), the sparse depth buffer and its
# line and face passes (sdepth), and against their double-precision references image edges
# (imgedge), the pinhole camera and pose (camera), filled triangles (raster), vertex projection
# (xform) and clipping at the near plane and the guard band (clip); the tracker's pose score
# against a dense z-buffer (track) and its particle filter on a synthetic cube sequence (particles);
# the tracker front end's readers of frames, cameras, poses and orientations (track input);
# view clamping,
# mc_octree_render's contract on hand-made and random scenes, hole filling (cmocka,
# tests/unit/test_*.c), and the freestanding build of runtime/src under gcc and clang.
#
# Prints one line per check, "ok - NAME" or "not ok - NAME: why", and exits non-zero if any failed.
# How the programs are built (each check runs once in make test):
#   by default, the programs at config.h's MC_FRAC_BITS (15: every program) with ASan + UBSan into
#   build/san/unit, and fixed point and views at the extreme formats 8 and 24 plain (-O2) into
#   build/tests/unit; then the freestanding builds;
#   SANITIZE=1: every program with ASan + UBSan, at the formats in UNIT_SAN_FORMATS (default 15;
#   make stress: "15 8 24"), no freestanding builds;
#   SANITIZE=0: every program plain (-O2), at 15, 8 and 24, and the freestanding builds.
# UNIT_SWITCH_ALL=1: the renderer's leaf switch at every level and target of the freestanding builds
# (by default at -O2 for gcc and the Cortex-M0 only), and in the plain test_view programs (by default
# the loop form, as under the sanitizers); make stress sets it.
# UNIT_OPT_LEVELS: the optimisation levels of the freestanding builds for every target (make stress:
# all five). By default "-O0 -O2 -Os" for the Cortex-M0 (no inlining, the firmware's level, the size
# level: where a 32-bit target's helper calls differ most, and clang's warnings and its soft-float
# calls, which no helper allows, show), "-O2" for gcc on x86-64 (its no-floating-point build), and
# clang on x86-64 not at all (what it checks, the M0 build checks; the web suite builds the runtime
# with clang for wasm32 too).
set -u
cd "$(dirname "$0")/../.." || exit 1

TAP_PREFIX=""
. tests/lib.sh
# use_build san|plain: the flags and directory the programs built next take; the renderer takes its
# loop form (leaves, below; plain builds with UNIT_SWITCH_ALL=1: the switch)
use_build() {
    if [ "$1" = san ]; then out=build/san/unit flags=$SAN_FLAGS leaves=(-DMC_LEAF_SWITCH=0)
    else out=build/tests/unit flags="-O2 -g" leaves=(-DMC_LEAF_SWITCH=0); fi
    [ "$1" = plain ] && [ "${UNIT_SWITCH_ALL:-0}" = 1 ] && leaves=()
    mkdir -p "$out"
}
# build_for FORMAT: the build the programs at that MC_FRAC_BITS take
build_for() {
    case ${SANITIZE:-} in
        1) use_build san ;;
        0) use_build plain ;;
        *) if [ "$1" = 15 ]; then use_build san; else use_build plain; fi ;;
    esac
}
build_for 15
CC_UNIT=${CC_UNIT:-gcc}
RT_CFLAGS=$(mkvar RT_CFLAGS)   # -std=c99 -ffreestanding -Wall -Wextra -Werror -Iruntime/include

# ---- cmocka programs ---------------------------------------------------------------------------
# The runtime is compiled into each test program. test_view's copy reports every plotted point to
# the test (MC_PLOT_HOOK), which checks it lies on the target.
hook='-DMC_PLOT_HOOK(fx,fy,c)=do { extern void mc_test_plot_hook(int32_t, int32_t, const uint8_t *); mc_test_plot_hook((fx), (fy), (c)); } while (0)'

# run_cmocka PREFIX PROGRAM: runs a cmocka program in TAP mode, rewriting "ok N - test" into
# "ok - PREFIX test" and "not ok N - test" into "not ok - PREFIX test: <the failure message>". A
# program that stops early (a sanitizer report, a crash) is one more failure.
run_cmocka() {
    local pfx=$1 prog=$2 log="$2.log" rc plan n
    CMOCKA_MESSAGE_OUTPUT=TAP "$prog" >"$log" 2>&1
    rc=$?
    awk -v pfx="$pfx" -v countfile="$log.count" '
        function flush() {
            if (pending != "") print pending (reason != "" ? ": " reason : "")
            pending = ""; reason = ""; collecting = 0
        }
        /^1\.\.[0-9]+$/ { plan = substr($0, 4); next }
        /^ok [0-9]+ - / { flush(); sub(/^ok [0-9]+ - /, ""); print "ok - " pfx $0; n++; note = ""; next }
        # cmocka skip(): "not ok N # SKIP test", the reason the test printed last
        /^not ok [0-9]+ # SKIP / {
            flush(); sub(/^not ok [0-9]+ # SKIP /, "")
            print "ok - " pfx $0 " # SKIP " (note != "" ? note : "skipped by the test"); n++; note = ""; next
        }
        /^not ok [0-9]+ - / {
            flush(); sub(/^not ok [0-9]+ - /, ""); pending = "not ok - " pfx $0; reason = err; err = ""
            collecting = 1; n++; next
        }
        /^ERROR: / { m = $0; sub(/^ERROR: /, "", m); if (err == "") err = m; next }
        /^# (ok|not ok) - / { flush(); next }                  # cmocka group summary
        /^# info/ { flush(); print; next }
        /^# / {
            if (collecting) { m = $0; sub(/^# /, "", m); reason = reason (reason != "" ? "; " : "") m }
            else print
            next
        }
        { flush(); print "# " $0; note = $0 }
        END { flush(); print n + 0, plan + 0 > countfile }
    ' "$log"
    read -r n plan <"$log.count"
    [ "$rc" -ne 0 ] && status=1    # cmocka exits with the number of failed tests
    if [ "$rc" -ne 0 ] && { [ "$n" -lt "$plan" ] || [ "$plan" -eq 0 ]; }; then
        local why
        why=$(grep -m1 -E 'runtime error|ERROR: AddressSanitizer|ERROR: LeakSanitizer|Segmentation|Aborted' "$log" |
            oneline)
        notok "${pfx}program" "exited with status $rc after $n of $plan tests${why:+: $why} (see $log)"
    fi
}

# The runtime a test program links: an archive of runtime/src compiled with the program's own flags,
# built once per set of flags and shared by every program with that set (compiling the runtime is
# most of this suite's time). test_view's has the renderer; the others test number helpers and never
# draw, so theirs leaves it out: its leaf switch is most of the compile time (several times more
# under the sanitizers). A test that needs a left-out file fails to link.
# runtime_archive WITH_RENDERER FLAGS...: prints the archive's path; the compiler's messages go to
# ARCHIVE.log. With RT_ONLY set (runtime/src basenames), the archive holds those sources only: the
# programs at the extreme formats have an archive each, and the rest of runtime/src compiled at
# that format would be linked by no program (a source such a program comes to need fails its link,
# and is added to its RT_ONLY below).
runtime_archive() {
    local renderer=$1 key dir f ok=1
    shift
    key=$(echo "$CC_UNIT $flags $renderer ${RT_ONLY:-} $*" | md5sum | cut -c1-12)
    dir=$out/rt-$key
    # made again when a runtime source or header changed since
    if [ -f "$dir/libmodelc.a" ] && [ -n "$(find runtime/src runtime/include -newer "$dir/libmodelc.a" -print -quit)" ]; then
        rm -f "$dir/libmodelc.a"
    fi
    if [ ! -f "$dir/libmodelc.a" ]; then
        rm -rf "$dir"
        mkdir -p "$dir"
        : >"$dir.log"
        local objs=() o
        for f in runtime/src/*.c; do
            [ "$renderer" = 1 ] || [ "$(basename "$f")" != octree_render.c ] || continue
            [ -z "${RT_ONLY:-}" ] || [[ " $RT_ONLY " == *" $(basename "$f" .c) "* ]] || continue
            # compiled as the Makefile compiles the runtime (RT_CFLAGS: C99, freestanding), through the
            # shared object cache (tests/lib.sh cc_obj): the sources the program's macros do not reach
            # are compiled once for all the archives with these flags (and, under the sanitizers, for the
            # other suites' sanitized runtimes: tests/sanitize/, finish/, gen/clip.sh)
            # shellcheck disable=SC2086
            o=$(cc_obj "$f" $CC_UNIT $flags $RT_CFLAGS "$@" 2>>"$dir.log") && objs+=("$o") || ok=0
        done
        if [ "$ok" = 1 ] && ar rcs "$dir/libmodelc.a.tmp" "${objs[@]}" 2>>"$dir.log"; then
            mv "$dir/libmodelc.a.tmp" "$dir/libmodelc.a"
        fi
    fi
    echo "$dir/libmodelc.a"
}

build_and_run() {   # build_and_run PREFIX NAME EXTRA_FLAGS...
    local pfx=$1 name=$2 lib renderer=0
    shift 2
    local prog="$out/$name"
    [ "${name%%-*}" = test_view ] && renderer=1
    # the flags are the program's and the runtime archive's; a flag written @FLAG is the program's
    # only (with its own copy of a runtime source given after it, which then stands in for the
    # archive's); source files (runtime/ref/...) are compiled into the program
    local cflags=() pflags=() extra=() a
    for a in "$@"; do
        case $a in *.c) extra+=("$a") ;; @*) pflags+=("${a#@}") ;; *) cflags+=("$a") ;; esac
    done
    lib=$(runtime_archive "$renderer" "${cflags[@]}")
    if [ ! -f "$lib" ]; then
        notok "${pfx}build" "the runtime archive: $(grep -m 3 -E 'error|warning' "${lib%/libmodelc.a}.log" | oneline)"
        return
    fi
    # shellcheck disable=SC2086
    if ! $CC_UNIT -std=gnu11 $flags -Wall -Wextra -Werror -Iruntime/include "${cflags[@]}" "${pflags[@]}" -o "$prog" \
        "tests/unit/${name%%-*}.c" "${extra[@]}" "$lib" -lcmocka -lm >"$prog.build.log" 2>&1; then
        notok "${pfx}build" "$(head -n 5 "$prog.build.log" | oneline)"
        return
    fi
    run_cmocka "$pfx" "$prog"
}

# fixed point and views at the default and both extreme MC_FRAC_BITS (F=15 is config.h's default:
# that program shares the archive of the programs below). Under the sanitizers the default only: the
# other formats change the numbers, not how memory is used, and each is a runtime archive to
# compile with them (the plain run checks all three).
formats="15 8 24"
[ "${SANITIZE:-}" = 1 ] && formats=${UNIT_SAN_FORMATS:-15}
for f in $formats; do
    build_for "$f"
    fb=() only=""
    [ "$f" = 15 ] || fb=(-DMC_FRAC_BITS=$f) only=fixed
    RT_ONLY=$only build_and_run "unit: fixed F=$f: " "test_fixed-f$f" "${fb[@]}"
done
build_for 15
build_and_run "unit: trig: " test_trig
build_and_run "unit: bits, rng, chunk: " test_bits
# the renderer's child lists in the other slot width too (child_bits.h: nibbles on 32-bit targets)
build_and_run "unit: bits, child lists in nibbles: " test_bits-n4 "@-DMC_CHILD_BITS=4"
# the bit helpers' other ways: portable C99, and the compiler's builtin where x86-64 takes assembly
build_and_run "unit: bits, portable C99: " test_bits-c99 "@-DMC_BITS_BUILTINS=0"
build_and_run "unit: bits, builtins without assembly: " test_bits-noasm "@-DMC_BITS_ASM=0"
build_and_run "unit: pmesh: " test_pmesh
build_and_run "unit: mesh face: " test_mesh_face
# the host viewer's automatic level of detail (host code: doubles, libm), in a simulated loop
build_and_run "unit: lod auto: " test_lod_auto runtime/front/host/lod_auto.c
# test_line counts the walk's steps (MC_LINE_STEP_HOOK) to check work follows on-target pixels: its
# own line.c with the hook, in front of the default archive
linehook='-DMC_LINE_STEP_HOOK()=do { extern unsigned long mc_test_line_steps; mc_test_line_steps++; } while (0)'
# both forms of the walk's steps (config.h MC_LINE_SELECT: branches, masks), whatever the default
build_and_run "unit: line: " test_line-w0 "@-DMC_LINE_SELECT=0" "@$linehook" runtime/src/line.c
build_and_run "unit: line, the walk's masks: " test_line-w1 "@-DMC_LINE_SELECT=1" "@$linehook" runtime/src/line.c
build_and_run "unit: raster: " test_raster runtime/ref/raster_ref.c
build_and_run "unit: xform: " test_xform runtime/ref/xform_ref.c
build_and_run "unit: clip: " test_clip runtime/ref/xform_ref.c
build_and_run "unit: sdepth: " test_sdepth
build_and_run "unit: imgedge: " test_imgedge runtime/ref/imgedge_ref.c
build_and_run "unit: camera: " test_camera runtime/ref/camera_ref.c
build_and_run "unit: track: " test_track
build_and_run "unit: particles: " test_particles
build_and_run "unit: detect: " test_detect
# the tracker front end's input readers (host-only C: runtime/front/track/), and the track_input
# fuzzer's check, which replays its findings (tests/fuzz/regress/track_input/)
build_and_run "unit: track input: " test_track_input runtime/front/track/track_input.c tests/fuzz/fuzz_track_input.c
# test_view checks the one-pixel-per-leaf contract, so its views default to one-pixel splats
# (footprints: tests/finish/ and tests/stress/). The renderer takes its loop form (MC_LEAF_SWITCH=0):
# the same per-leaf code as the switch, which takes some 30 times longer to compile under the
# sanitizers and 6 s of CPU at -O2 for each format; tests/stress/ checks the switch against the loop
# byte for byte at F=8 and 24 and against the reference, and make stress checks it here
# (UNIT_SWITCH_ALL=1: in the plain builds) and under the sanitizers (tests/render/, RENDER_SAN_SWITCH=1).
for f in $formats; do
    build_for "$f"
    only=""
    [ "$f" = 15 ] || only="finish fixed octree_render sintab target trig xform"
    RT_ONLY=$only build_and_run "unit: view F=$f: " "test_view-f$f" -DMC_FRAC_BITS=$f -DMC_SPLAT_DEFAULT_MODE=1 "${leaves[@]}" "$hook"
done

# ---- freestanding builds -----------------------------------------------------------------------
# (not repeated under SANITIZE=1: they check the compilers' output, not run anything)
if [ "${SANITIZE:-}" != 1 ]; then
    use_build plain
    fs=$out/freestanding
    rm -rf "$fs"
    mkdir -p "$fs"
    FS_FLAGS="-std=c99 -ffreestanding -nostdlib -Wall -Wextra -Werror -pedantic -Iruntime/include"
    # symbols a freestanding object may still need: the compilers' own helper libraries (libgcc,
    # compiler-rt: 64-bit division on 32-bit targets, ARM EABI helpers) and the GOT of PIC code.
    # Not the memory functions (memcpy, memset, __aeabi_memcpy...): those come from a libc.
    helpers='^(__(u?(div|mod|mul)[sdt]i3|u?divmod[sdt]i4|(ash[lr]|lshr)[sdt]i3|(popcount|ctz|clz|parity|ffs|bswap)[sdt]i2|cmp[dt]i2|ucmp[dt]i2|neg[dt]i2|aeabi_(l|ui|i|ul)(div|divmod|mul|asr|lsl|lsr|cmp|ucmp)|aeabi_(idiv|uidiv|idivmod|uidivmod|ldivmod|uldivmod|lmul|llsl|llsr|lasr|lcmp|ulcmp))|_GLOBAL_OFFSET_TABLE_)$'

    # fs_build TAG "CC FLAGS...": compiles every runtime/src/*.c at several optimisation levels into
    # $fs/TAG/O*/, with only the compiler's own headers on the include path (-nostdinc), and prints
    # the problems, if any. On x86-64 (tags gcc and clang) the -O2 build also has
    # -mgeneral-regs-only: gcc then refuses any floating-point operation and clang turns it into
    # soft-float library calls (__muldf3...), which no compiler helper below allows.
    fs_build() {
        local tag=$1 cc=$2 inc o f dir nofloat
        inc=$($cc -print-file-name=include 2>/dev/null)
        case $cc in clang*) inc="$(clang -print-resource-dir)/include" ;; esac
        for o in $levels; do
            dir="$fs/$tag/O${o#-O}"
            mkdir -p "$dir"
            nofloat=""
            [ "$o" = -O2 ] && { [ "$tag" = gcc ] || [ "$tag" = clang ]; } && nofloat=-mgeneral-regs-only
            for f in runtime/src/*.c; do
                # the renderer's leaf switch at -O2 only (the firmware's level; each of its cases is
                # the loop form's body for one mask, so the loop shows the helper calls at the
                # other levels, at a fifth of the compile time), and there for gcc (x86-64, also the
                # no-floating-point build) and the Cortex-M0 only: clang's x86-64 build takes the loop
                # (tests/fw/ compiles the switch for Cortex-M3 and M4 as well)
                leaf=""
                [ "$(basename "$f")" = octree_render.c ] && [ "${UNIT_SWITCH_ALL:-0}" != 1 ] &&
                    { [ "$o" != -O2 ] || [ "$tag" = clang ]; } && leaf=-DMC_LEAF_SWITCH=0
                # shellcheck disable=SC2086
                if ! $cc $o $nofloat $leaf $FS_FLAGS -nostdinc -isystem "$inc" -c -o "$dir/$(basename "$f" .c).o" "$f" \
                    >"$dir/$(basename "$f" .c).log" 2>&1; then
                    echo "$f at $o: $(head -n 3 "$dir/$(basename "$f" .c).log" | oneline)"
                fi
            done
        done
    }
    # fs_undefined TAG LD NM: links each optimisation level's objects into one relocatable object
    # (ld -r) and prints the undefined symbols that are not compiler helpers
    fs_undefined() {
        local tag=$1 ld=$2 nm=$3 dir bad
        for dir in "$fs/$tag"/O*; do
            if ! $ld -r -o "$dir/runtime.o" "$dir"/*.o 2>"$dir/ld.log"; then
                echo "ld -r failed at -O${dir##*/O}: $(head -n 2 "$dir/ld.log" | oneline)"
                continue
            fi
            bad=$($nm -u "$dir/runtime.o" | awk '{print $NF}' | grep -Ev "$helpers" | tr '\n' ' ')
            [ -n "$bad" ] && echo "-O${dir##*/O} needs: $bad"
            $nm -u "$dir/runtime.o" | awk '{print $NF}' >"$dir/undefined.txt"
        done
    }

    targets=("gcc|gcc|ld|nm|-O2" "clang|clang|ld|nm|")
    # a 32-bit target where 64-bit arithmetic needs helpers: a Cortex-M0 (no divide, no long
    # multiply), when clang supports it (tests/fw/ links the runtime for Cortex-M3 and M4 with gcc,
    # where a helper outside libgcc would fail the link)
    if echo 'int x;' | clang --target=thumbv6m-none-eabi -ffreestanding -x c -c -o /dev/null - 2>/dev/null &&
        command -v ld.lld >/dev/null; then
        targets+=("clang-cortex-m0|clang --target=thumbv6m-none-eabi -mcpu=cortex-m0|ld.lld|llvm-nm|-O0 -O2 -Os")
    fi
    for t in "${targets[@]}"; do
        IFS='|' read -r tag cc ld nm levels <<<"$t"
        levels=${UNIT_OPT_LEVELS:-$levels}   # (x86-64 adds -O2 below for its no-floating-point build)
        [ -n "$levels" ] || continue
        nofloat_name="unit: freestanding: $tag builds runtime/src with -mgeneral-regs-only (no floating point)"
        case $tag in gcc | clang) [[ " $levels " == *" -O2 "* ]] || levels+=" -O2" ;; *) nofloat_name="" ;; esac
        problems=$(fs_build "$tag" "$cc")
        if [ -z "$problems" ]; then
            ok "unit: freestanding: $tag compiles runtime/src with $FS_FLAGS -nostdinc at $levels"
        else
            notok "unit: freestanding: $tag compiles runtime/src with $FS_FLAGS -nostdinc at $levels" \
                "$(echo "$problems" | oneline)"
            [ -n "$nofloat_name" ] && notok "$nofloat_name" "$(echo "$problems" | grep -e '-O2' | oneline)"
            continue
        fi
        problems=$(fs_undefined "$tag" "$ld" "$nm")
        if [ -z "$problems" ]; then
            ok "unit: freestanding: $tag runtime object (ld -r) has no undefined symbols but compiler helpers"
        else
            notok "unit: freestanding: $tag runtime object (ld -r) has no undefined symbols but compiler helpers" \
                "$(echo "$problems" | oneline)"
        fi
        # the -O2 build had -mgeneral-regs-only: it compiled, and needs no soft-float routine
        if [ -n "$nofloat_name" ]; then
            check_problems "$nofloat_name" "$(echo "$problems" | grep -e '^-O2 ' | oneline)"
        fi
    done

    # the runtime's sources and headers, comments removed: no float/double types, no float literals
    # (another number type for positions is a test-side header: config.h MC_POS_HEADER)
    problems=""
    float_re='\b(float|double|_Complex|_Imaginary|__float128|_Float\d+x?)\b|(?<![\w.])(\d+\.\d*|\.\d+|\d+[eE][+-]?\d+)(?![\w.])'
    rt_files=(runtime/src/*.c runtime/src/*.h runtime/include/modelc/*.h)
    # all the files through one gcc first; only when something is found, file by file to name them
    if gcc -fpreprocessed -dD -E -P "${rt_files[@]}" 2>/dev/null | sed 's/"\([^"\\]\|\\.\)*"/""/g' | grep -qP "$float_re"; then
        for f in "${rt_files[@]}"; do
            hits=$(gcc -fpreprocessed -dD -E -P "$f" 2>/dev/null | sed 's/"\([^"\\]\|\\.\)*"/""/g' | grep -nP "$float_re" |
                head -n 3 | oneline)
            [ -n "$hits" ] && problems+="$f: $hits "
        done
        [ -n "$problems" ] || problems="found in the files together, in none alone"
    fi
    if [ -z "$problems" ]; then ok "unit: freestanding: no float, double or floating literal in runtime/src and runtime/include"
    else notok "unit: freestanding: no float, double or floating literal in runtime/src and runtime/include" "$problems"; fi

    # includes: the standard headers every freestanding C99 compiler provides, the runtime's own
    # headers, and the user's MC_CONFIG_FILE and MC_POS_HEADER
    check_includes() {
        local f line name problems=""
        for f in "$@"; do
            while IFS= read -r line; do
                name=$(echo "$line" | sed -E 's/^[[:space:]]*#[[:space:]]*include[[:space:]]*//; s/[[:space:]]*(\/[*/].*)?$//')
                case $name in
                    '<stdint.h>' | '<stddef.h>' | '<stdbool.h>' | '<limits.h>' | MC_CONFIG_FILE | MC_POS_HEADER) ;;
                    \"*\")
                        name=${name#\"}
                        name=${name%\"}
                        [ -f "runtime/include/$name" ] || [ -f "runtime/include/modelc/$name" ] || [ -f "runtime/src/$name" ] ||
                            problems+="$f: $name is not a runtime header; "
                        ;;
                    *) problems+="$f: $name; " ;;
                esac
            done < <(grep -E '^[[:space:]]*#[[:space:]]*include' "$f")
        done
        echo "$problems"
    }
    problems=$(check_includes runtime/include/modelc/*.h runtime/src/*.h)
    if [ -z "$problems" ]; then ok "unit: freestanding: runtime headers include only <stdint.h> <stddef.h> <stdbool.h> <limits.h> and runtime headers"
    else notok "unit: freestanding: runtime headers include only <stdint.h> <stddef.h> <stdbool.h> <limits.h> and runtime headers" "$problems"; fi
    problems=$(check_includes runtime/src/*.c)
    if [ -z "$problems" ]; then ok "unit: freestanding: runtime sources include only <stdint.h> <stddef.h> <stdbool.h> <limits.h> and runtime headers"
    else notok "unit: freestanding: runtime sources include only <stdint.h> <stddef.h> <stdbool.h> <limits.h> and runtime headers" "$problems"; fi
fi

exit $status
