#!/usr/bin/env bash
# Numerical stress (tests/stress/stress.c says what is checked and derives the error bound): random
# views of bunny00 baked at depth 6 into build/stress/ (small chunks, so chunk boundaries are crossed
# often), rendered by a runtime compiled with the plot hook into the test.
#   STRESS_VIEWS   views of the optimised run (default 20000: the suite took 290 s of CPU at 100000)
#   STRESS_SAN_VIEWS  views of the run under ASan + UBSan (-fno-sanitize-recover=all; default 3000;
#                  0 skips it), and of the float build's run under them plus float-cast-overflow
#   STRESS_JOBS    processes the optimised run is split into, each with its own seed (default 1)
#   STRESS_F_VIEWS views of each of three more optimised runs: MC_FRAC_BITS 8 and 24, and the float
#                  build (tests/accuracy/pos_single.h; default STRESS_VIEWS / 10)
#   STRESS_SEED    first seed (default 1)
#   STRESS_ALT_SWITCH=1  the float build against the branch depth test with the leaf switch (default:
#                  with the loop, one compile of the switch fewer)
# make stress runs it with 10^7 views on two processes and STRESS_ALT_SWITCH=1.
# Prints one line per check, "ok - NAME" or "not ok - NAME: why"; exits non-zero if any failed.
set -u
cd "$(dirname "$0")/../.." || exit 1
VIEWS=${STRESS_VIEWS:-20000}
SAN_VIEWS=${STRESS_SAN_VIEWS:-3000}
JOBS=${STRESS_JOBS:-1}
F_VIEWS=${STRESS_F_VIEWS:-$(((VIEWS + 9) / 10))}
SEED=${STRESS_SEED:-1}
out=build/stress
model=bunny00
bake=$out/$model
TAP_PREFIX="stress: "
. tests/lib.sh
mkdir -p "$out"

src=build/models/bunny00.off
[ -f "$src" ] || make -s "$src" >"$out/models.log" 2>&1
[ -x build/bin/modelc ] || make -s gen >"$out/gen.log" 2>&1
if [ ! -f "$bake/budget.json" ] || [ "$bake/budget.json" -ot build/bin/modelc ]; then
    rm -rf "$bake"
    if ! build/bin/modelc "$src" -o "$out" --name "$model" --depth 6 --screen 64x64 --chunk-bytes 512 \
        --file-bytes 65536 --quiet >"$out/bake.log" 2>&1; then
        notok "bake $model at depth 6" "$(head -n 3 "$out/bake.log" | oneline)"
        exit 1
    fi
fi

# build OUTPUT FLAGS...: the runtime (the select form of the depth test, plus LEAVES) with the plot
# hook into the test, and a second copy of octree_render.c (and target.c's mc_clear) in the form ALT
# (named ALT_NAME; entry points renamed, no plot hook) that stress.c checks against it (check 5)
# (the point renderer's modules only, not the mesh and tracker ones that stress.c never calls: one
# missing fails the link). The runtime is compiled as the Makefile compiles it (RT_CFLAGS), with
# tests/render/'s plot hook in octree_render.c, through the shared object cache (tests/lib.sh cc_obj):
# the -O2 and float builds' objects are tests/render/suite.sh's default and float forms', the
# sanitized build's its sanitized run's and tests/unit/suite.sh's, compiled once for the whole run.
POINT_RT=(camera finish fixed octree_render sintab target trig xform)
rt_cflags=$(mkvar RT_CFLAGS)   # -std=c99 -ffreestanding -Wall -Wextra -Werror -Iruntime/include
hook=('-DMC_PLOT_HOOK(fx,fy,c)=record_point(fx,fy,c)' -include tests/render/hook.h)
LEAVES=() ALT=(-DMC_DEPTH_SELECT=0) ALT_NAME="the branch depth test (MC_DEPTH_SELECT=0)"
build() {
    local prog=$1 f o h objs=()
    shift
    # shellcheck disable=SC2068
    gcc -std=c99 "$@" "${ALT[@]}" -DMC_TEST_CLIPPED_SQUARES=1 -Dmc_octree_render=mc_octree_render_alt -Dmc_octree_lod_depth=mc_octree_lod_depth_alt -Dmc_clear=mc_clear_alt -Wall -Wextra -Werror \
        -Iruntime/include -c -o "$prog.alt.o" runtime/src/octree_render.c >"$prog.log" 2>&1 || return 1
    # shellcheck disable=SC2068
    gcc -std=c99 "$@" -Dmc_clear=mc_clear_alt -Wall -Wextra -Werror \
        -Iruntime/include -c -o "$prog.alt-target.o" runtime/src/target.c >>"$prog.log" 2>&1 || return 1
    for f in "${POINT_RT[@]}"; do
        h=()
        [ "$f" = octree_render ] && h=("${hook[@]}")
        # shellcheck disable=SC2086
        o=$(cc_obj "runtime/src/$f.c" gcc "$@" $rt_cflags "${LEAVES[@]}" -DMC_DEPTH_SELECT=1 "${h[@]}" 2>>"$prog.log") ||
            return 1
        objs+=("$o")
    done
    gcc -std=c99 -D_POSIX_C_SOURCE=200809L "$@" -DSTRESS_ALT=1 \
        "-DSTRESS_ALT_FORM=\"$ALT_NAME; footprints over a pixel through the clipped path\"" -Wall -Wextra -Werror \
        -Iruntime/include -Iruntime/ref "${hook[@]}" \
        -o "$prog" tests/stress/stress.c runtime/ref/ref.c "${objs[@]}" "$prog.alt.o" "$prog.alt-target.o" "$bake"/*.c -lm >>"$prog.log" 2>&1
}

# ---- optimised, JOBS processes with consecutive seeds ---------------------------------------------
rm -f "$out"/run.*.log   # a run's verdict reads its own logs only
if build "$out/stress" -O2 -g; then
    pids=()
    per=$(((VIEWS + JOBS - 1) / JOBS))
    t0=$(date +%s.%N)
    for j in $(seq 0 $((JOBS - 1))); do
        "$out/stress" "$per" $((SEED + j)) "stress seed $((SEED + j))" >"$out/run.$j.log" 2>&1 &
        pids+=($!)
    done
    rcs=0
    for p in "${pids[@]}"; do wait "$p" || rcs=1; done
    t1=$(date +%s.%N)
    for j in $(seq 0 $((JOBS - 1))); do
        grep -E '^(ok|not ok) ' "$out/run.$j.log" | sed 's/^\(ok\|not ok\) - /&stress: /'
        grep '^#' "$out/run.$j.log"
    done
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
    echo "# $((per * JOBS)) views in $JOBS process(es): $secs s wall clock"
    if [ "$rcs" -ne 0 ] && ! grep -q '^not ok' "$out"/run.[0-9]*.log; then
        notok "optimised run" "a process failed without reporting: $(tail -n 3 "$out"/run.[0-9]*.log | oneline)"
    fi
    grep -q '^not ok' "$out"/run.[0-9]*.log && status=1
else
    notok "build (-O2)" "$(head -n 5 "$out/stress.log" | oneline)"
fi

# ---- the extreme fixed-point formats, MC_FRAC_BITS 8 and 24 (targets at most MC_TARGET_MAX, 8x8 at
# 24), and the float build (tests/accuracy/pos_single.h, held to its own bound: stress.c) ------------
float_flags=(-DMC_FLOAT=1 '-DMC_POS_HEADER="pos_single.h"' -Itests/accuracy)
for name in F=8 F=24 float; do
    # each against another form: the loop walk of the leaves at F=8, the loop and the branch at F=24
    # and in the float build (the branch against the select, both with the switch, is the -O2 run's;
    # STRESS_ALT_SWITCH=1, make stress: the float build's too, a switch more to compile). F=8 walks
    # 2x2 squares a level d-1 node at a time (MC_FLAT_SQUARES=0, the firmware's way), the -O2 run
    # a level d-2 node at a time (x86-64's default); the float build can only walk them the first way.
    case $name in
        F=8) vflags=(-DMC_FRAC_BITS=8 -DMC_FLAT_SQUARES=0) seed_off=108
            ALT=(-DMC_DEPTH_SELECT=1 -DMC_LEAF_SWITCH=0) ALT_NAME="the unrolled leaf loop (MC_LEAF_SWITCH=0)" ;;
        F=24) vflags=(-DMC_FRAC_BITS=24) seed_off=124
            ALT=(-DMC_DEPTH_SELECT=0 -DMC_LEAF_SWITCH=0)
            ALT_NAME="the unrolled leaf loop with the branch depth test (MC_LEAF_SWITCH=0, MC_DEPTH_SELECT=0)" ;;
        float) vflags=("${float_flags[@]}") seed_off=200
            ALT=(-DMC_DEPTH_SELECT=0 -DMC_LEAF_SWITCH=0)
            ALT_NAME="the unrolled leaf loop with the branch depth test (MC_LEAF_SWITCH=0, MC_DEPTH_SELECT=0)"
            [ "${STRESS_ALT_SWITCH:-0}" = 1 ] && ALT=(-DMC_DEPTH_SELECT=0) ALT_NAME="the branch depth test (MC_DEPTH_SELECT=0)" ;;
    esac
    flag="${vflags[*]}"
    if build "$out/stress-$name" -O2 -g "${vflags[@]}"; then
        "$out/stress-$name" "$F_VIEWS" $((SEED + seed_off)) "stress $name" >"$out/run.$name.log" 2>&1
        rc=$?
        grep -E '^(ok|not ok) ' "$out/run.$name.log" | sed 's/^\(ok\|not ok\) - /&stress: /'
        grep '^#' "$out/run.$name.log"
        if [ "$rc" -ne 0 ]; then
            grep -q '^not ok' "$out/run.$name.log" || notok "$name run" "status $rc: $(tail -n 3 "$out/run.$name.log" | oneline)"
            status=1
        fi
    else
        notok "build ($flag)" "$(head -n 5 "$out/stress-$name.log" | oneline)"
    fi
done

# ---- under sanitizers -----------------------------------------------------------------------------
# san_run NAME SEED_OFFSET WHAT SANITIZERS [FLAGS...]: builds and runs SAN_VIEWS views under the given
# -fsanitize list, halting on the first report
san_run() {
    local name=$1 seed_off=$2 what=$3 san=$4
    shift 4
    # shellcheck disable=SC2068
    if build "$out/stress-$name" -O1 -g1 "$@" -fsanitize="$san" -fno-sanitize-recover=all -fno-omit-frame-pointer; then
        "$out/stress-$name" "$SAN_VIEWS" $((SEED + seed_off)) "stress $name" >"$out/run.$name.log" 2>&1
        local rc=$? rep
        grep -E '^(ok|not ok) ' "$out/run.$name.log" | sed 's/^\(ok\|not ok\) - /&stress: /'
        grep '^#' "$out/run.$name.log"
        rep=$(sanitizer_report "$out/run.$name.log")
        if [ "$rc" -ne 0 ] || [ -n "$rep" ]; then
            grep -q '^not ok' "$out/run.$name.log" || notok "$SAN_VIEWS views of $what under $san" "status $rc: ${rep:-see $out/run.$name.log}"
            status=1
        else
            ok "$SAN_VIEWS views of $what under -fsanitize=$san -fno-sanitize-recover=all: no report"
        fi
    else
        notok "build ($what, sanitizers)" "$(head -n 5 "$out/stress-$name.log" | oneline)"
    fi
}
# Both copies take the loop walk of the leaves there (the same per-leaf code as the switch, which
# compiles some 30 times slower under the sanitizers; make stress checks the switch under them).
if [ "$SAN_VIEWS" -gt 0 ]; then
    LEAVES=(-DMC_LEAF_SWITCH=0)
    ALT=(-DMC_DEPTH_SELECT=0 -DMC_LEAF_SWITCH=0) ALT_NAME="the branch depth test (MC_DEPTH_SELECT=0)"
    san_run san 1000 "the runtime" address,undefined
    # the float build, with float-to-integer conversions out of range and divisions by zero trapped too
    san_run fsan 2000 "the float build" address,undefined,float-cast-overflow,float-divide-by-zero "${float_flags[@]}"
fi
exit $status
