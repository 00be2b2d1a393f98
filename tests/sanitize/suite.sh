#!/usr/bin/env bash
# The test suite once more under AddressSanitizer and UndefinedBehaviorSanitizer:
#   - tests/render/suite.sh (if present) with SANITIZE=1: it builds its own programs with the
#     sanitizers into build/san/render (tests/unit/suite.sh runs its programs at the default
#     MC_FRAC_BITS under them itself)
#   - a sanitized generator build/san/bin/modelc (the Makefile's GEN_SRC + build/gen/templates.cpp,
#     compiled as the Makefile does plus the sanitizer flags): tests/gen/errors.sh (if present) with it, and one real
#     bake of nefertiti, which must give the same files as the normal generator's bake; and the
#     fuzzers' findings (tests/fuzz/suite.sh) replayed through it
#   - a sanitized bunny00 viewer (the renderer's leaves in their loop form): a few views, --png and
#     --bench 20, with the same pictures as the normal viewer
# SAN_PARTS chooses: "runtime" (the default, in make test: render, viewer) and/or "generator"
# (make fuzz runs it: the sanitized generator takes minutes to compile, and the fuzzers run the
# generator under the same sanitizers).
# Any sanitizer report fails the check it happens in (the programs halt on the first one).
# Passed-through lines are prefixed "san: " so their names stay unique.
# Prints one line per check, "ok - NAME" or "not ok - NAME: why"; exits non-zero if any failed.
set -u
cd "$(dirname "$0")/../.." || exit 1
san=build/san
mkdir -p "$san/bin" "$san/gen" "$san/viewer"
TAP_PREFIX="san: "
. tests/lib.sh
check() { check_problems "$@"; }   # check NAME PROBLEMS
jobs_max=$(nproc 2>/dev/null || echo 2)
SAN_PARTS=${SAN_PARTS:-runtime}
has_part() { [[ " $SAN_PARTS " == *" $1 "* ]]; }

# pass_through LABEL LOG STATUS [PREFIX]: the suite's check lines with "san: PREFIX" added; a failing
# suite that reported no failure (a crash, a sanitizer abort outside a check) is one more failure
pass_through() {
    local label=$1 log=$2 rc=$3 pfx=${4:-}
    grep -E '^(ok|not ok) ' "$log" | sed -E "s/^(ok|not ok) - /\\1 - san: $pfx/"
    if [ "$rc" -ne 0 ]; then
        status=1
        grep -q '^not ok ' "$log" ||
            notok "$label" "exited with status $rc without reporting a failure: $(sanitizer_report "$log") (see $log)"
    fi
}

# ---- the render suite ---------------------------------------------------------------------------
if has_part runtime; then
if [ -e tests/render/suite.sh ]; then
    SANITIZE=1 tests/render/suite.sh >"$san/render-suite.log" 2>&1
    pass_through "render suite" "$san/render-suite.log" $? "render: "
fi
fi   # runtime

# ---- sanitized generator -----------------------------------------------------------------------
if has_part generator; then
# compiled like the Makefile's $(BUILD)/gen/%.o, objects rebuilt when a source, a header or the flags
# changed; several at a time, as they are slow
build_generator() {
    local cxx cxxflags libs src obj flags_now failed=0 pids=() srcs=() objs=()
    cxx=$(mkvar CXX)
    cxxflags="$(mkvar GEN_CXXFLAGS) $SAN_FLAGS -DMC_OPENMESH_ASSERTS=1"   # OpenMesh's own checks too (gen/pmesh.cpp)
    libs=$(mkvar GEN_LIBS)
    make -s build/gen/templates.cpp >"$san/gen/templates.log" 2>&1 || {
        echo "cannot generate build/gen/templates.cpp: $(head -n 3 "$san/gen/templates.log" | oneline)"
        return 1
    }
    flags_now="$cxx $cxxflags"
    [ "$(cat "$san/gen/flags" 2>/dev/null)" = "$flags_now" ] || rm -f "$san"/gen/*.o
    echo "$flags_now" >"$san/gen/flags"
    local newest_hdr
    newest_hdr=$(ls -t $(mkvar GEN_HDR) 2>/dev/null | head -n 1)
    rm -f "$san"/gen/*.o.tmp
    for src in $(mkvar GEN_SRC) build/gen/templates.cpp; do
        obj=$san/gen/$(echo "${src%.cpp}" | tr '/' '_').o
        objs+=("$obj")
        if [ -f "$obj" ] && [ "$obj" -nt "$src" ] && { [ -z "$newest_hdr" ] || [ "$obj" -nt "$newest_hdr" ]; }; then
            continue
        fi
        while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do wait -n; done
        # shellcheck disable=SC2086
        ($cxx $cxxflags -c -o "$obj.tmp" "$src" >"$obj.log" 2>&1 && mv "$obj.tmp" "$obj") &
        pids+=($!)
        srcs+=("$src")
    done
    local i
    for i in "${!pids[@]}"; do
        if ! wait "${pids[$i]}"; then
            echo "compiling ${srcs[$i]} failed: $(grep -m3 -E 'error' "$san/gen/$(echo "${srcs[$i]%.cpp}" | tr '/' '_').o.log" | oneline)"
            failed=1
        fi
    done
    [ "$failed" = 0 ] || return 1
    # shellcheck disable=SC2086
    $cxx $cxxflags -o "$san/bin/modelc" "${objs[@]}" $libs >"$san/gen/link.log" 2>&1 ||
        { echo "link failed: $(head -n 3 "$san/gen/link.log" | oneline)"; return 1; }
}
problems=$(build_generator)
check "generator builds with $SAN_FLAGS into $san/bin/modelc" "$problems"
if [ -z "$problems" ]; then
    # errors.sh takes the generator as $1
    bash tests/gen/errors.sh "$san/bin/modelc" >"$san/gen-errors.log" 2>&1
    pass_through "gen errors.sh with the sanitized generator" "$san/gen-errors.log" $? "gen errors: "
    # the fuzzers' findings (tests/fuzz/regress/), replayed the same way
    tests/fuzz/suite.sh "$san/bin/modelc" >"$san/fuzz-regress.log" 2>&1
    pass_through "fuzz regressions with the sanitized generator" "$san/fuzz-regress.log" $?
    # one real bake: nefertiti, with the catalogue's options
    model=nefertiti
    src=build/models/$(basename "$(mkvar "$model.src")")
    [ -f "$src" ] || make -s "$src" >"$san/models.log" 2>&1
    rm -rf "$san/bake"
    mkdir -p "$san/bake"
    # shellcheck disable=SC2046
    "$san/bin/modelc" "$src" -o "$san/bake" --name "$model" $(mkvar "$model.opts") $(mkvar BAKE_OPTS) \
        >"$san/bake.log" 2>&1
    rc=$?
    name="sanitized generator bakes $src ($(mkvar "$model.opts")) without a sanitizer report"
    if [ "$rc" -ne 0 ] || [ -n "$(sanitizer_report "$san/bake.log")" ] || [ ! -f "$san/bake/$model/budget.json" ]; then
        notok "$name" "status $rc: $( (sanitizer_report "$san/bake.log"; tail -n 2 "$san/bake.log") | oneline)"
    else
        ok "$name"
        # the same files as the normal generator's bake (when that bake is up to date)
        name="sanitized generator's bake of $model equals build/$model/ byte for byte"
        newest=$(ls -t gen/* templates/* build/bin/modelc 2>/dev/null | head -n 1)
        if [ -f "build/$model/budget.json" ] && [ "build/$model/budget.json" -nt "$newest" ]; then
            diffs=""
            for f in "$san/bake/$model"/*; do
                cmp -s "$f" "build/$model/$(basename "$f")" || diffs+="$(basename "$f") "
            done
            for f in "build/$model"/*.c "build/$model"/*.h "build/$model"/*.json; do
                [ -e "$san/bake/$model/$(basename "$f")" ] || diffs+="$(basename "$f") (missing) "
            done
            check "$name" "${diffs:+differ: $diffs}"
        else
            skip "$name" "build/$model is older than the generator: run make views"
        fi
    fi
fi
fi   # generator

# ---- sanitized viewer --------------------------------------------------------------------------
if has_part runtime; then
m=bunny00
v=$san/viewer/$m-view
name="viewer $m builds with $SAN_FLAGS"
if [ ! -f "build/$m/budget.json" ]; then
    notok "$name" "build/$m is not baked (run make views)"
else
    cc=$(mkvar CC)
    rt_cflags=$(mkvar RT_CFLAGS)
    host_cflags=$(mkvar HOST_CFLAGS)
    ldflags=$(mkvar VIEW_LDFLAGS)
    problems=""
    objs=()
    # the renderer's leaves in their loop form (MC_LEAF_SWITCH=0): the same per-leaf code as the
    # switch, which compiles some 30 times slower under the sanitizers (make stress checks the
    # switch under them, tests/render/ with RENDER_SAN_SWITCH=1); the pictures are compared with
    # the normal viewer's, which has the switch
    # (the runtime through the shared object cache, tests/lib.sh cc_obj: the same sanitized objects as
    # the unit suite's sanitized programs, tests/finish/'s and tests/gen/clip.sh's, compiled once)
    for f in runtime/src/*.c; do
        log=$san/viewer/$(basename "$f" .c).o.log
        # shellcheck disable=SC2086
        if o=$(cc_obj "$f" $cc $SAN_FLAGS -DMC_LEAF_SWITCH=0 $rt_cflags 2>"$log"); then objs+=("$o")
        else problems+="$f: $(head -n 2 "$log" | oneline); "; fi
    done
    for f in "build/$m"/*.c; do
        o=$san/viewer/$(basename "$f" .c).o
        # shellcheck disable=SC2086
        $cc $SAN_FLAGS -DMC_LEAF_SWITCH=0 $rt_cflags -c -o "$o" "$f" >"$o.log" 2>&1 || problems+="$f: $(head -n 2 "$o.log" | oneline); "
        objs+=("$o")
    done
    for f in runtime/front/host/*.c runtime/front/common/*.c; do
        o=$san/viewer/host-$(basename "$f" .c).o
        # shellcheck disable=SC2086
        $cc $SAN_FLAGS $host_cflags -c -o "$o" "$f" >"$o.log" 2>&1 || problems+="$f: $(head -n 2 "$o.log" | oneline); "
        objs+=("$o")
    done
    if [ -z "$problems" ]; then
        # shellcheck disable=SC2086
        $cc $SAN_FLAGS -o "$v" "${objs[@]}" $ldflags >"$san/viewer/link.log" 2>&1 ||
            problems="link: $(head -n 3 "$san/viewer/link.log" | oneline)"
    fi
    check "$name" "$problems"
    if [ -z "$problems" ]; then
        normal=build/$m/$m-view
        views=(
            ""
            "--yaw 30 --pitch 20 --roll 10"
            "--zoom 8"
            "--zoom 8 --yaw 123 --pitch -40"
            "--zoom 0.015625"
            "--perspective"
            "--perspective --zoom 8 --yaw 200 --pitch 15"
            "--perspective --zoom 64"
            "--size 640x480 --yaw -75"
            "--size 1x1"
            "--size 7x480 --zoom 3"
            "--depth 1"
            "--depth 5 --no-finish --roll 33"
        )
        for args in "${views[@]}"; do
            n=$(echo "render ${args:-default}" | tr -c 'a-zA-Z0-9.\n-' '_')
            name="viewer $m --ppm ${args:-(default view)}: no sanitizer report, same picture as the normal viewer"
            # shellcheck disable=SC2086
            timeout 300 "$v" $args --ppm "$san/viewer/$n.ppm" >"$san/viewer/$n.log" 2>&1
            rc=$?
            rep=$(sanitizer_report "$san/viewer/$n.log")
            if [ "$rc" -ne 0 ] || [ -n "$rep" ]; then
                notok "$name" "status $rc: ${rep:-$(tail -n 2 "$san/viewer/$n.log" | oneline)}"
                continue
            fi
            # shellcheck disable=SC2086
            if [ -x "$normal" ] && "$normal" $args --ppm "$san/viewer/$n.normal.ppm" >/dev/null 2>&1; then
                cmp -s "$san/viewer/$n.ppm" "$san/viewer/$n.normal.ppm" && problems="" ||
                    problems="the picture differs from $normal's"
            else
                problems="$normal could not render the same view"
            fi
            check "$name" "$problems"
        done
        for args in "--png $san/viewer/out.png --yaw 45" "--bench 20" "--bench 20 --perspective --zoom 4"; do
            name="viewer $m $args: no sanitizer report"
            n=$(echo "${args%% *}-$RANDOM" | tr -c 'a-zA-Z0-9\n-' '_')
            # shellcheck disable=SC2086
            timeout 600 "$v" $args >"$san/viewer/$n.log" 2>&1
            rc=$?
            rep=$(sanitizer_report "$san/viewer/$n.log")
            if [ "$rc" -ne 0 ] || [ -n "$rep" ]; then notok "$name" "status $rc: ${rep:-$(tail -n 2 "$san/viewer/$n.log" | oneline)}"
            else ok "$name"; fi
        done
    fi
fi
fi   # runtime

exit $status
