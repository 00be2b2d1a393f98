#!/usr/bin/env bash
# Budgets, --fit, --emit lib, monochrome scenes and palettes: budget failures name every
# item over budget with the right numbers and leave no output; --fit picks the finest depth that
# fits (bunny00 on lm3s6965evb: 256 KiB flash, 64 KiB RAM) and depth + 1 does not fit; --emit lib
# writes no app binding and the README's library example compiles, links and renders; a monochrome
# model stores no colours and draws what the coloured one draws; every palette entry is used; the
# runtime cost tables in gen/runtime_costs.hpp still match a fresh -fstack-usage / size build.
set -u
cd "$(dirname "$0")/../.."
modelc=${1:-build/bin/modelc}
TAP_PREFIX="budget: "
. tests/lib.sh
temp_dir
nok() { notok "$1"; }
check() { check_cmd "$@"; }   # check NAME COMMAND...
json() { python3 -c "import json,sys; b=json.load(open(sys.argv[1])); print($2)" "$1"; }
bunny=build/models/bunny00.off
rt_cc="gcc -std=c99 -O2 -Wall -Wextra -Werror -Iruntime/include"
rt=$(rt_objs | tr '\n' ' ')   # the runtime's objects as the Makefile builds them (one function a section)

# the slow part first, in the background: bunny00 voxelized at depth 8 for lm3s6965evb
lm="--flash-budget 256K --ram-budget 64KiB --stack-budget 8K"
"$modelc" "$bunny" -q --depth 8 --screen 160x128 $lm --fit --emit lib -o "$tmp/fit" >"$tmp/fit.out" 2>"$tmp/fit.err" &
fit_pid=$!
"$modelc" "$bunny" -q --depth 8 --screen 160x128 $lm -o "$tmp/fit8" >/dev/null 2>"$tmp/fit8.err" &
fit8_pid=$!

# --- options -----------------------------------------------------------------------------------
"$modelc" "$bunny" -q --depth 3 --flash-budget 12X -o "$tmp/bad" 2>"$tmp/e.txt"
check "--flash-budget 12X is refused with status 2 and one line" test $? = 2 -a "$(wc -l <"$tmp/e.txt")" = 1 -a ! -e "$tmp/bad"
"$modelc" "$bunny" -q --depth 3 --fit -o "$tmp/bad" 2>"$tmp/e.txt"
check "--fit without a budget is refused with status 2" test $? = 2 -a ! -e "$tmp/bad"

# --- budget failures ---------------------------------------------------------------------------
"$modelc" "$bunny" -q --depth 6 --screen 320x240 -o "$tmp/ref"
b=$tmp/ref/bunny00/budget.json
flash=$(json "$b" 'b["flash"]["image"]') ram=$(json "$b" 'b["ram"]["image"]') stack=$(json "$b" 'b["stack"]["bound"]')
check "budget.json: flash image = data + descriptors + runtime code, ram = 3 bytes a pixel, stack bound recorded" python3 - "$b" <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))
f = b["flash"]
assert f["image"] == f["total"] + f["descriptors"] + f["runtime_code"]["total"], f
assert f["runtime_code"]["total"] == sum(v for k, v in f["runtime_code"].items() if k not in ("total", "leaf_switch"))
assert b["ram"]["image"] == 3 * 320 * 240 + b["ram"]["runtime_static"]
assert b["stack"]["bound"] > 2000 and b["stack"]["frames"]["walk_frames"] == 4
assert set(b["modules"]) == {"fixed", "trig", "xform", "target", "octree_render", "finish"}, b["modules"]
PY
fb=$((flash - 1000)) sb=$((stack - 100))
mkdir -p "$tmp/over"
"$modelc" "$bunny" -q --depth 6 --screen 320x240 --flash-budget $fb --ram-budget 64K --stack-budget $sb -o "$tmp/over" 2>"$tmp/e.txt"
st=$?
want="modelc: over budget: flash $flash bytes > $fb (by 1000); ram $ram bytes > 65536 (by $((ram - 65536))); stack $stack bytes > $sb (by 100)"
check "over budget: exit 1 and one line naming flash, ram and stack with the right numbers" test "$st" = 1 -a "$(cat "$tmp/e.txt")" = "$want"
[ "$st" = 1 ] && [ "$(cat "$tmp/e.txt")" = "$want" ] || echo "#   got: $(cat "$tmp/e.txt")  want: $want"
check "over budget: nothing written" test -z "$(ls -A "$tmp/over")"
"$modelc" "$bunny" -q --depth 6 --screen 320x240 --flash-budget $fb -o "$tmp/over" 2>"$tmp/e.txt"
check "only flash over: the message names flash alone" test "$(cat "$tmp/e.txt")" = "modelc: over budget: flash $flash bytes > $fb (by 1000)"
"$modelc" "$bunny" -q --depth 6 --screen 320x240 --flash-budget $flash --ram-budget $ram --stack-budget $stack -o "$tmp/exact"
check "budgets equal to the need pass, and budget.json records them" test "$(json "$tmp/exact/bunny00/budget.json" 'b["budgets"]["flash"]["limit"] - b["budgets"]["flash"]["used"]')" = 0
check "a bake within budget is the bake without budgets (data files identical)" diff -r -x budget.json "$tmp/ref/bunny00" "$tmp/exact/bunny00"

# --- --fit on a small depth: cut from one voxelization, deterministic ------------------------
fb=$(json "$b" 'b["flash"]["image"] - b["flash"]["colors"] // 2')   # depth 6 cannot fit, depth 5 can
"$modelc" "$bunny" -q --depth 6 --screen 320x240 --flash-budget $fb --fit -o "$tmp/f1" >"$tmp/f1.out"
"$modelc" "$bunny" -q --depth 6 --screen 320x240 --flash-budget $fb --fit -o "$tmp/f2" >/dev/null
check "--fit (depth 6, flash $fb): one line, depth 5" grep -q '^modelc: fit: depth 5 (of 6)' "$tmp/f1.out"
check "--fit output is deterministic" diff -r "$tmp/f1/bunny00" "$tmp/f2/bunny00"
check "--fit cuts the depth-6 octree: levels 0..5 have the depth-6 bake's node counts" python3 - "$b" "$tmp/f1/bunny00/budget.json" <<'PY'
import json, sys
a, c = (json.load(open(p)) for p in sys.argv[1:])
assert c["depth"] == 5 and c["points_per_level"] == a["points_per_level"][:6], (a["points_per_level"], c["points_per_level"])
assert c["flash"]["image"] <= c["budgets"]["flash"]["limit"]
PY

# --- monochrome ---------------------------------------------------------------------------------
"$modelc" "$bunny" -q --depth 6 --name colr --emit lib -o "$tmp/m" &
colr_pid=$!
"$modelc" "$bunny" -q --depth 6 --name mono --palette 1 --emit lib -o "$tmp/m"
wait $colr_pid
check "monochrome: budget.json has no colour bytes, the data files no colour arrays" \
    test "$(json "$tmp/m/mono/budget.json" '"%d %d" % (b["flash"]["colors"], b["palette_entries"])')" = "0 1" -a \
    -z "$(grep -l '_c[0-9]*_[0-9]*\[' "$tmp/m/mono"/*.c)"
if $rt_cc -I"$tmp/m/colr" -I"$tmp/m/mono" -o "$tmp/mono" tests/lib/mono.c $rt "$tmp/m/colr"/*.c \
    "$tmp/m/mono"/*.c 2>"$tmp/mono.log"; then
    "$tmp/mono" | sed 's/^\(not \)\{0,1\}ok - /&budget: /' | tee "$tmp/mono.out"
    grep -q '^not ok' "$tmp/mono.out" && fails=$((fails + 1))
else
    nok "monochrome test build: $(head -n 3 "$tmp/mono.log" | tr '\n' ' ')"
fi

# --- palettes: every stored entry is used -------------------------------------------------------
"$modelc" build/models/b9_training.ply -q --depth 6 --palette 16 --up z -o "$tmp/p"
used() {   # every colour index 0..n-1 occurs, none >= n
    python3 - "$1" <<'PY'
import glob, json, re, sys
d = sys.argv[1]
n = json.load(open(d + "/budget.json"))["palette_entries"]
seen = set()
for f in glob.glob(d + "/*_data_*.c"):
    for body in re.findall(r"_c\d+_\d+\[\d+\] = \{(.*?)\};", open(f).read(), re.S):
        seen.update(int(x) for x in re.findall(r"\d+", body))
assert seen == set(range(n)), (n, sorted(set(range(n)) - seen), sorted(seen - set(range(n))))
PY
}
check "palette entries all used (b9_training, --palette 16)" used "$tmp/p/b9_training"
check "palette entries all used (bunny00, depth 6)" used "$tmp/ref/bunny00"
check "palette entries all used (bunny00 cut to depth 5 by --fit)" used "$tmp/f1/bunny00"

# --- --emit lib and the README example --------------------------------------------------------
"$modelc" "$bunny" -q --depth 5 --emit lib -o "$tmp/lib"
check "--emit lib writes the model's .h/.c and budget.json, no app binding" \
    test -f "$tmp/lib/bunny00/bunny00.h" -a -f "$tmp/lib/bunny00/bunny00_octree.c" -a -f "$tmp/lib/bunny00/bunny00_model.c" -a ! -e "$tmp/lib/bunny00/bunny00_app.c" -a \
    "$(json "$tmp/lib/bunny00/budget.json" 'b["emit"]')" = lib
check "--emit app (the default) writes the app binding" test -f "$tmp/ref/bunny00/bunny00_app.c"
check "README's library example is tests/lib/example.c, verbatim" python3 - <<'PY'
readme = open("README.md").read()
sec = readme.split("## Use as a library", 1)[1].split("\n## ", 1)[0]
code = sec.split("```c\n", 1)[1].split("```", 1)[0]
assert code == open("tests/lib/example.c").read()
PY
if $rt_cc -I"$tmp/lib/bunny00" -o "$tmp/example" tests/lib/example.c $rt "$tmp/lib/bunny00"/*.c 2>"$tmp/ex.log" &&
    "$tmp/example" >"$tmp/example.out"; then
    check "the README example links with the runtime and renders 8 frames, each lighting pixels" \
        test "$(grep -c 'pixels lit' "$tmp/example.out")" = 8 -a -z "$(grep ': 0 pixels' "$tmp/example.out")"
else
    nok "the README example builds and runs: $(head -n 3 "$tmp/ex.log" | tr '\n' ' ')"
fi
# what a program does not call is not linked: the example draws and fills one-pixel holes only
if $rt_cc -ffunction-sections -fdata-sections -I"$tmp/lib/bunny00" -o "$tmp/example-gc" tests/lib/example.c \
    $rt "$tmp/lib/bunny00"/*.c -Wl,--gc-sections 2>"$tmp/gc.log"; then
    syms=$(nm "$tmp/example-gc")
    check "--gc-sections: the example links mc_octree_render and mc_finish_pixel_holes but not mc_finish_scanline_holes or mc_finish" \
        test -n "$(grep ' T mc_octree_render$' <<<"$syms")" -a -n "$(grep ' T mc_finish_pixel_holes$' <<<"$syms")" -a \
        -z "$(grep ' mc_finish_scanline_holes$\| mc_finish$' <<<"$syms")"
else
    nok "--gc-sections build of the example: $(head -n 3 "$tmp/gc.log" | tr '\n' ' ')"
fi
over=('-DMC_BUNNY00_SECTION=__attribute__((section(".models")))' '-DMC_BUNNY00_ALIGN=__attribute__((aligned(4)))'
      -DMC_BUNNY00_PREFIX=board_)
if $rt_cc "${over[@]}" -I"$tmp/lib/bunny00" -o "$tmp/example2" tests/lib/example.c $rt "$tmp/lib/bunny00"/*.c 2>"$tmp/ex2.log"; then
    syms=$(nm "$tmp/example2")
    check "section, alignment and prefix macros: .models section, global symbols board_*, same frames" \
        test -n "$(objdump -h "$tmp/example2" | grep ' \.models ')" -a -n "$(grep ' board_model$' <<<"$syms")" -a \
        -n "$(grep ' board_octree$' <<<"$syms")" -a \
        -z "$(grep ' [A-Z] mc_model_bunny00$\| [A-Z] mc_octree_bunny00$\| [A-Z] mc_bunny00_' <<<"$syms")" -a "$("$tmp/example2")" = "$(cat "$tmp/example.out")"
else
    nok "section, alignment and prefix macros build: $(head -n 3 "$tmp/ex2.log" | tr '\n' ' ')"
fi

# --- the runtime cost tables against a fresh build ----------------------------------------------
measure() {   # CC FLAGS... : compile runtime/src with -fstack-usage into $tmp/su-$1
    local dir=$tmp/su-$1 cc=$2; shift 2
    mkdir -p "$dir"
    for f in runtime/src/*.c; do
        (cd "$dir" && $cc -std=c99 -ffreestanding -I"$OLDPWD/runtime/include" -O2 -fstack-usage \
            -ffunction-sections -fdata-sections "$@" -c "$OLDPWD/$f") || return 1
    done
}
tables() {   # KIND DIR SIZE-TOOL: every frame in the table >= measured; every octree_render.c function listed
    python3 - "$@" <<'PY'
import glob, re, subprocess, sys
kind, d, size = sys.argv[1:]
src = open("gen/runtime_costs.hpp").read()
frames = {f: (int(a), int(h)) for f, a, h in re.findall(r'\{"([\w.]+)", (\d+), (\d+)\}', src.split("kFrames[]")[1].split("};")[0])}
track = {f: (int(a), int(h)) for f, a, h in re.findall(r'\{"([\w.]+)", (\d+), (\d+)\}', src.split("kTrackFrames[]")[1].split("};")[0])}
col = 0 if kind == "arm" else 1
bad = []
for su in glob.glob(d + "/*.su"):
    mod = su.split("/")[-1][:-3]
    for line in open(su):
        loc, n, qual = line.split("\t")
        fn = loc.split(":")[-1]
        if fn in frames:
            if int(n) > frames[fn][col]:
                bad.append("%s: %s bytes, table %d" % (fn, n, frames[fn][col]))
        elif mod == "octree_render":
            bad.append("%s (octree_render.c) missing from kFrames" % fn)
        if fn in track:
            if int(n) > track[fn][col]:
                bad.append("%s: %s bytes, kTrackFrames %d" % (fn, n, track[fn][col]))
        elif mod in ("particles", "detect", "track") and fn not in ("mc_filter_init", "mc_filter_weight"):
            bad.append("%s (%s.c) missing from kTrackFrames" % (fn, mod))
        if "static" not in qual and "bounded" not in qual:   # bounded: arguments pushed around a call
            bad.append("%s: %s stack" % (fn, qual.strip()))
if kind == "arm":
    table = {m: int(a) for m, a, _ in re.findall(r'\{"(\w+)", (\d+), (\d+), "', src)}
    out = subprocess.run([size] + sorted(glob.glob(d + "/*.o")), capture_output=True, text=True).stdout
    got = {}
    for line in out.splitlines()[1:]:
        f = line.split()
        mod = f[5].split("/")[-1][:-2]
        mod = "trig" if mod == "sintab" else mod
        got[mod] = got.get(mod, 0) + int(f[0]) + int(f[1])
    for m, n in table.items():
        if abs(got.get(m, 0) - n) > max(256, n // 10):
            bad.append("code of %s: %d bytes, table %d" % (m, got.get(m, 0), n))
if bad:
    print("#", "; ".join(bad))
    sys.exit(1)
PY
}
if measure host gcc -DMC_FLAT_SQUARES=0; then   # the firmware's configuration (runtime_costs.hpp)
    check "stack tables >= host gcc -O2 -fstack-usage for every function; every octree_render.c function in kFrames, every particles.c, detect.c and track.c one in kTrackFrames" tables host "$tmp/su-host" size
else
    nok "host -fstack-usage build of runtime/src"
fi
if command -v arm-none-eabi-gcc >/dev/null; then
    if measure arm arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb; then
        check "stack table >= arm-none-eabi-gcc Cortex-M4 -fstack-usage; module code within 10% of the table" tables arm "$tmp/su-arm" arm-none-eabi-size
    else
        nok "arm -fstack-usage build of runtime/src"
    fi
else
    skip "arm tables" "arm-none-eabi-gcc not installed (make deps)"
fi

# --- bunny00 on lm3s6965evb ---------------------------------------------------------------------
wait $fit_pid
st=$?
fit_line=$(cat "$tmp/fit.out")
check "--fit lm3s6965evb (256K flash, 64K RAM, 160x128): exit 0, one line naming depth 7 of 8" \
    test "$st" = 0 -a "$(wc -l <"$tmp/fit.out")" = 1 -a -n "$(grep '^modelc: fit: depth 7 (of 8)' <<<"$fit_line")"
echo "# $fit_line"
check "--fit lm3s6965evb: the bake it wrote is within every budget, at 160x128" python3 - "$tmp/fit/bunny00/budget.json" <<'PY'
import json, sys
b = json.load(open(sys.argv[1]))
assert b["depth"] == 7 and b["screen"] == [160, 128] and b["emit"] == "lib", (b["depth"], b["screen"])
assert b["flash"]["image"] <= 262144 and b["ram"]["image"] <= 65536 and b["stack"]["bound"] <= 8192
PY
wait $fit8_pid
st=$?
check "lm3s6965evb at depth 8 (depth + 1) is over the flash budget: exit 1, names flash" \
    test "$st" = 1 -a -n "$(grep '^modelc: over budget: flash [0-9]* bytes > 262144 (by [0-9]*)$' "$tmp/fit8.err")" -a ! -e "$tmp/fit8"
if command -v arm-none-eabi-gcc >/dev/null && [ -f "$tmp/fit/bunny00/budget.json" ]; then
    # the estimate against the real thing: the model and the runtime modules budget.json lists
    # (trig is trig.c and its table sintab.c) compiled for Cortex-M3
    mkdir -p "$tmp/armfit"
    srcs=()
    for m in $(json "$tmp/fit/bunny00/budget.json" '" ".join(b["modules"])'); do
        srcs+=("$PWD/runtime/src/$m.c")
        [ "$m" = trig ] && srcs+=("$PWD/runtime/src/sintab.c")
    done
    if (cd "$tmp/armfit" && for f in "${srcs[@]}" "$tmp/fit/bunny00"/*.c; do
            arm-none-eabi-gcc -std=c99 -ffreestanding -mcpu=cortex-m3 -mthumb -O2 -I"$OLDPWD/runtime/include" \
                -ffunction-sections -fdata-sections -c "$f" || exit 1; done); then
        real=$(arm-none-eabi-size "$tmp/armfit"/*.o | awk 'NR > 1 {s += $1 + $2} END {print s}')
        est=$(json "$tmp/fit/bunny00/budget.json" 'b["flash"]["image"] - b["flash"]["runtime_code"]["libgcc"]')
        check "flash estimate $est within 3% of the Cortex-M3 objects' text+data ($real)" \
            test $((100 * (est > real ? est - real : real - est) / real)) -lt 3
    else
        nok "Cortex-M3 build of the fitted bake"
    fi
fi
exit $((fails > 0))
