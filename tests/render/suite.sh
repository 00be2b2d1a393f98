#!/usr/bin/env bash
# Renders of every catalogue model against the double-precision reference (compare.c says what is
# checked and why the tolerances are what they are). SANITIZE=1 builds with ASan + UBSan (three models).
set -u
cd "$(dirname "$0")/../.."
. tests/lib.sh
flags="-O2 -g"
out=build/tests/render
if [ "${SANITIZE:-0}" = 1 ]; then
    flags=$SAN_FLAGS
    out=build/san/render
fi
mkdir -p "$out"
models=$(make -s -f models/catalogue.mk -f - <<<'print: ; @echo $(CATALOGUE)' print)
# Under the sanitizers (tests/sanitize/suite.sh) one model of each kind, a mesh, a coloured point set
# and a point set with normals, stands for the catalogue: each comparison runs several times slower
# under ASan + UBSan, and the plain run of this suite compares all eight.
[ "${SANITIZE:-0}" = 1 ] && models=${RENDER_SAN_MODELS:-bunny00 b9_training kitten}
# Under them the leaves take the loop form (MC_LEAF_SWITCH=0) unless RENDER_SAN_SWITCH=1 (make stress):
# the switch's cases are the loop's body for one mask each, and it takes some 30 s of CPU to compile
# under the sanitizers; make test checks the switch against the loop byte for byte in tests/stress/,
# with guard zones, and the loop here under ASan + UBSan.
default_flags=()
[ "${SANITIZE:-0}" = 1 ] && [ "${RENDER_SAN_SWITCH:-0}" != 1 ] && default_flags=(-DMC_LEAF_SWITCH=0)
status=0
hook=('-DMC_PLOT_HOOK(fx,fy,c)=record_point(fx,fy,c)' -include tests/render/hook.h)
rt_cflags=$(mkvar RT_CFLAGS)   # -std=c99 -ffreestanding -Wall -Wextra -Werror -Iruntime/include
# obj_of FORM FILE: where FILE's object for that form is kept
obj_of() { local f=${2%.c}; echo "$out/obj-$1/${f//\//_}.o"; }
# compile FORM FILE FLAGS...: FILE's object for one form of the renderer, built once (the runtime,
# the reference and compare.c are the same for every model: only the model's data is linked anew)
# The runtime is compiled as the Makefile compiles it (RT_CFLAGS), through the shared object cache
# (tests/lib.sh cc_obj), the plot hook in octree_render.c only (no other source calls it): a source
# the form's macros do not reach is compiled once for every form, and with the same flags elsewhere
# (tests/stress/suite.sh, which has the same hook; under the sanitizers tests/unit/suite.sh's
# runtime archive) once for the whole run. The object is linked into the form's directory, so that
# the form's next models do not ask the cache again.
compile() {
    local form=$1 src=$2 obj o h=()
    shift 2
    obj=$(obj_of "$form" "$src")
    mkdir -p "$out/obj-$form"
    if [ "${src#runtime/src/}" != "$src" ]; then
        [ "$src" = runtime/src/octree_render.c ] && h=("${hook[@]}")
        # shellcheck disable=SC2086
        o=$(cc_obj "$src" gcc $flags $rt_cflags "$@" "${h[@]}" 2>>"$out/build-$form.log") &&
            ln -sf "$PWD/$o" "$obj" || return 1
    else
        # shellcheck disable=SC2086
        gcc -std=c99 $flags -Wall -Wextra -Werror "$@" -Iruntime/include -Iruntime/ref "${hook[@]}" \
            -c -o "$obj.tmp" "$src" 2>>"$out/build-$form.log" && mv "$obj.tmp" "$obj" || return 1
    fi
    echo "$obj"
}
# build FORM MODEL FLAGS...: links $out/compare-[FORM-]MODEL; prints why on failure
build() {
    local form=$1 m=$2 objs=() f o
    shift 2
    rm -rf "$out/obj-$form-$m"
    for f in tests/render/compare.c runtime/ref/ref.c runtime/src/*.c; do
        o=$(obj_of "$form" "$f")
        [ -f "$o" ] || o=$(compile "$form" "$f" "$@") || { head -n 3 "$out/build-$form.log" | tr '\n' ' '; return 1; }
        objs+=("$o")
    done
    for f in "build/$m"/*.c; do
        o=$(compile "$form-$m" "$f" "$@") || { head -n 3 "$out/build-$form-$m.log" | tr '\n' ' '; return 1; }
        objs+=("$o")
    done
    gcc $flags -o "$out/compare-${form#default-}$m" "${objs[@]}" -lm 2>"$out/link-$form-$m.log" ||
        { head -n 3 "$out/link-$form-$m.log" | tr '\n' ' '; return 1; }
}
rm -rf "$out"/obj-* "$out"/build-*.log
for m in $models; do
    if [ ! -f "build/$m/budget.json" ]; then
        echo "not ok - $m: not baked (run make views)"; status=1; continue
    fi
    # the runtime is compiled into the test with the plot hook pointing at the recorder
    if ! why=$(build default- "$m" "${default_flags[@]}"); then
        echo "not ok - $m: test build failed: $why"; status=1; continue
    fi
    "$out/compare-$m" || status=1
done
# every form of the renderer (config.h): the depth test as a branch and as a select (the default
# depends on the CPU), the leaves as the unrolled loop instead of the switch, and float positions
# (measurement only; compare.c holds it to its own bound): the same comparison, names prefixed with
# the form. Not under the sanitizers: the stress suite's runs under them take these forms already
# (the loop with the select and with the branch, and the float build with float-cast-overflow too,
# over random views), and the default form above, the switch, is checked under them by make stress
# (RENDER_SAN_SWITCH=1).
m=bunny00
# (the float build: tests/accuracy/pos_single.h in place of runtime/src/pos.h, MC_FLOAT for the test)
float_flags=(-DMC_FLOAT=1 '-DMC_POS_HEADER="pos_single.h"' -Itests/accuracy)
forms="branch select loop float"
[ "${SANITIZE:-0}" = 1 ] && forms=""
for name in $forms; do
    case $name in
        branch) vflags=(-DMC_DEPTH_SELECT=0) ;;
        select) vflags=(-DMC_DEPTH_SELECT=1) ;;
        loop) vflags=(-DMC_LEAF_SWITCH=0) ;;
        float) vflags=("${float_flags[@]}") ;;
    esac
    if why=$(build "$name-" "$m" "${vflags[@]}"); then
        "$out/compare-$name-$m" | sed -E "s/^(ok|not ok) - /\1 - $name: /"
        [ "${PIPESTATUS[0]}" = 0 ] || status=1
    else
        echo "not ok - $name: $m: test build failed: $why"; status=1
    fi
done
exit $status
