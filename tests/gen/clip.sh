#!/usr/bin/env bash
# Clipping at the near plane and the guard band in whole frames (xform.h's clipping through
# mc_mesh_render and mc_mesh_lines), on bunny00 and fandisk baked --as both, with
# tests/gen/clip_check.c (its reference: tests/unit/test_clip.c's, in long doubles):
#   - the eye inside the model, 1/4 cube side from its centre, looking six ways, coarse and finest
#     levels: coverage where the reference is sure, each lone face's shade, nothing written outside
#     the target, the counts adding up (clipped + clipped away = faces with a flagged corner), the
#     flagged faces' facing as the reference's plane test, the line drawing as its edges' clipped
#     lines, the vertex cache changing nothing;
#   - magnified views (zoom 64 on 256 x 256) whose faces are cut at the band as well;
#   - random views across and beyond the clamped ranges, faces and lines with every flag, under
#     ASan + UBSan: no finding, guard zones untouched, the counts adding up; and the hidden lines
#     over the sparse depth buffer (its arrays allocated to the byte) showing the z-buffer way's.
# The two models are baked, built and checked side by side (two jobs).
#
# usage: tests/gen/clip.sh [MODELC]        (default build/bin/modelc)
set -u
cd "$(dirname "$0")/../.."
modelc=${1:-build/bin/modelc}
TAP_PREFIX="clip: "
. tests/lib.sh
temp_dir

# the runtime the sanitized checker is built with (the -O2 one links the viewers' objects, rt_objs)
runtime="pmesh mesh_render mesh_lines mesh_creases line raster sdepth xform xform_vertex target fixed trig sintab"
top=$PWD
opt="-std=c99 -O2 -Wall -Wextra -Werror -I$top/runtime/include"
san="-std=c99 $SAN_FLAGS -Wall -Wextra -Werror -I$top/runtime/include"

# objs DIR FLAGS FILE...: compiles the files (absolute paths) into DIR in one compiler run; DIR.ok
# or DIR.fail says how it went, DIR.log what the compiler said
objs() {
    local dir=$1 flags=$2
    shift 2
    mkdir -p "$dir"
    # shellcheck disable=SC2086
    if (cd "$dir" && gcc $flags -c "$@") >"$dir.log" 2>&1; then touch "$dir.ok"; else touch "$dir.fail"; return 1; fi
}

# the runtime: as the viewers have it (rt_objs), and under the sanitizers, built while the models bake
rt=$(rt_objs | tr '\n' ' ')
rt_san=$tmp/rt_san
# the sanitized runtime from the shared object cache (tests/lib.sh cc_obj), compiled as the Makefile
# compiles the runtime (RT_CFLAGS) plus the sanitizers: the same objects as tests/sanitize/'s viewer,
# tests/finish/'s and the unit suite's under SANITIZE=1; $rt_san.list names them
san_runtime() {
    local f o list=() rt_cflags
    rt_cflags=$(mkvar RT_CFLAGS)
    : >"$rt_san.log"
    for f in $runtime; do
        # shellcheck disable=SC2086
        o=$(cc_obj "runtime/src/$f.c" gcc $SAN_FLAGS $rt_cflags 2>>"$rt_san.log") || { touch "$rt_san.fail"; return 1; }
        list+=("$PWD/$o")
    done
    echo "${list[*]}" >"$rt_san.list"
    touch "$rt_san.ok"
}
san_runtime &

# wait_runtime: until the sanitized runtime is built (polled: a background subshell cannot wait for
# its parent's jobs); fails when it failed
wait_runtime() {
    local i
    for i in $(seq 1200); do
        [ -e "$rt_san.fail" ] && return 1
        [ -e "$rt_san.ok" ] && return 0
        sleep 0.1
    done
    return 1
}

# check_model MODEL NAME: bakes, builds and checks one model, printing its TAP lines
check_model() {
    local m=$1 name=$2 src V n dir v views count r
    # run LABEL COMMAND...: one check from a checker's "ok: ..." / "not ok: ..." line
    run() {
        local label=$1
        shift
        r=$("$@" 2>&1)
        if [[ $r == ok:* ]]; then ok "$label: ${r#ok: }"; else notok "$label" "$(echo "${r#not ok: }" | oneline)"; fi
    }
    src=$(model_file "$m") || { notok "$m: model file" "cannot extract it (make models)"; return; }
    if ! "$modelc" "$src" -o "$tmp" --name "$name" --depth 5 --as both -q >"$tmp/$name.log" 2>&1; then
        notok "$m: bakes --as both" "$(oneline <"$tmp/$name.log")"
        return
    fi
    local inc="-DPM=mc_pmesh_$name -include $tmp/$name/$name.h" sandata=san
    # bunny00's 7 MB of arrays are compiled once, uninstrumented (ASan then guards the runtime's and
    # the checker's memory, not reads past the bake's arrays; fandisk's are instrumented)
    [ "$name" = bun ] && sandata=opt
    # shellcheck disable=SC2086
    if ! wait_runtime || ! objs "$tmp/d_opt_$name" "$opt" "$tmp/$name"/*.c ||
        ! gcc $opt $inc -o "$tmp/check_$name" tests/gen/clip_check.c $rt "$tmp/d_opt_$name"/*.o -lm \
            >"$tmp/$name.cc" 2>&1 ||
        ! { [ "$name" = bun ] || objs "$tmp/d_san_$name" "$san" "$tmp/$name"/*.c; } ||
        ! gcc $san $inc -o "$tmp/check_$name-san" tests/gen/clip_check.c $(cat "$rt_san.list") "$tmp/d_${sandata}_$name"/*.o -lm \
            >"$tmp/$name.san.cc" 2>&1; then
        notok "$m: tests/gen/clip_check.c builds with the runtime and the bake (-O2, and $SAN_FLAGS)" \
            "$(cat "$rt_san.log" "$tmp"/d_*_"$name".log "$tmp/$name".*cc 2>/dev/null | head -n 3 | oneline)"
        return
    fi
    V=$(python3 -c "import json; print(json.load(open('$tmp/$name/budget.json'))['pmesh']['vertices'])")
    # the eye 1/4 cube side from the centre, looking along -z turned by yaw and pitch
    for n in 300 "$V"; do
        for dir in "0 0" "1024 0" "2048 0" "3072 0" "0 1024" "0 3072"; do
            # shellcheck disable=SC2086
            run "$m: level $n, eye inside, yaw/pitch $dir" "$tmp/check_$name" frame "$n" 160 120 $dir 65536 16384
        done
    done
    # magnified: faces cut at the band as well
    case $m in
        bunny00) views=("3058 2525 4194304 21579" "3291 155 4194304 21723") ;;
        *) views=("234 633 4194304 22930" "1922 4070 4194304 24996") ;;
    esac
    for v in "${views[@]}"; do
        # shellcheck disable=SC2086
        run "$m: level $V, 256x256, yaw pitch zoom eye $v" "$tmp/check_$name" frame "$V" 256 256 $v
    done
    # random views under the sanitizers (the finest level is slow there: fewer views of bunny00)
    case $m in bunny00) count=20 ;; *) count=200 ;; esac
    run "$m: $count random views under ASan + UBSan" "$tmp/check_$name-san" random "$count" 11
    run "$m: an inside frame under ASan + UBSan" "$tmp/check_$name-san" frame 2000 120 90 1024 300 65536 16384
}

check_model bunny00 bun >"$tmp/bun.tap" 2>&1 &
check_model fandisk fan >"$tmp/fan.tap" 2>&1 &
wait
cat "$tmp/bun.tap" "$tmp/fan.tap"
grep -q '^not ok' "$tmp/bun.tap" "$tmp/fan.tap" && status=1
# 16 checks a model: a model whose checks stopped short (a crash of this script's job) fails here
for f in bun fan; do
    n=$(grep -c '^\(not \)\?ok' "$tmp/$f.tap")
    [ "$n" -ge 16 ] || notok "$f: all 16 checks ran" "$n reported"
done
exit $status
