#!/usr/bin/env bash
# The whole test suite (make test). Builds what the tests need, runs every suite, prints each
# suite's checks, counts and time, and ends with exactly one line "N passed, N failed, N skipped".
# A suite prints one line per check (tests/tap.sh): "ok - NAME" (passed), "not ok - NAME: why"
# (failed) or "ok - NAME # SKIP why" (skipped: counted apart, never as a pass). A suite that exits
# non-zero without reporting a failure counts as one failed check, so a crash is never a pass.
# Exits non-zero when anything failed.
set -u
cd "$(dirname "$0")/.."
logdir=build/tests
mkdir -p "$logdir"

echo "building the generator, the runtime and the catalogue's viewers..."
if ! make -s -j"$(nproc)" gen views >"$logdir/build.log" 2>&1; then
    tail -n 30 "$logdir/build.log"
    echo "0 passed, 1 failed, 0 skipped"
    exit 1
fi

suites=(
    tests/unit/suite.sh       # fixed point, sine table, freestanding builds
    tests/gen/errors.sh       # malformed input: one error line, no output
    tests/gen/suite.sh        # determinism, chunks, budget
    tests/gen/views.sh        # --views: hidden-cell removal, frontal image unchanged
    tests/gen/budget.sh       # budgets, --fit, --emit lib, monochrome, palettes, runtime cost tables
    tests/fuzz/suite.sh       # the fuzzers' findings (tests/fuzz/regress/) replayed through modelc
    tests/render/suite.sh     # renders against the double-precision reference
    tests/host/suite.sh       # viewer binaries: no heap, options, interactive mode
    tests/sanitize/suite.sh   # the render and unit tests again under ASan + UBSan
    tests/fw/suite.sh         # firmware: Cortex-M3/M4 under QEMU, checksums equal the host's, budgets
    tests/stress/suite.sh     # 10^5 random views: guard zones, error bound, ASan + UBSan run
    tests/finish/suite.sh     # hole types 1-5 on synthetic images, fills and splats against a reference
    tests/accuracy/suite.sh   # the mesh reference renderer: synthetic meshes, bunny00 against its octree
)

skip_re='^ok .*# *[Ss][Kk][Ii][Pp]'
pass=0 fail=0 skip=0 times=()
for s in "${suites[@]}"; do
    label=${s#tests/}
    label=${label%.sh}
    label=${label%/suite}
    [ -x "$s" ] || { echo "not ok - $s: missing or not executable"; fail=$((fail + 1)); continue; }
    log="$logdir/$(echo "$s" | tr '/' '_').log"
    # wall time and the CPU time of the suite and its children (the machine may be shared)
    TIMEFORMAT='%R %U %S'
    { time "$s" >"$log" 2>&1; } 2>"$log.time"
    status=$?
    read -r wall user sys < <(tail -n 1 "$log.time")
    grep -E '^(ok|not ok) ' "$log" | sed "s|^|[$label] |"
    p=$(grep -E '^ok ' "$log" | grep -cvE "$skip_re")
    k=$(grep -cE "$skip_re" "$log")
    f=$(grep -c '^not ok ' "$log")
    if [ "$status" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "not ok - $s exited with status $status without reporting a failure (see $log)"
        tail -n 5 "$log"
        f=1
    fi
    cpu=$(echo "$user $sys" | awk '{ printf "%.1f", $1 + $2 }')
    line=$(printf '[%s] %.1f s wall, %s s CPU: %d passed, %d failed, %d skipped' "$label" "$wall" "$cpu" "$p" "$f" "$k")
    echo "$line"
    times+=("$line")
    pass=$((pass + p))
    fail=$((fail + f))
    skip=$((skip + k))
done
echo "times:"
printf '  %s\n' "${times[@]}"
echo "$pass passed, $fail failed, $skip skipped"
[ "$fail" -eq 0 ]
