#!/usr/bin/env bash
# The whole test suite (make test). Builds what the tests need, runs every suite, and ends with one
# line "N passed, N failed". A suite is a program or script that prints one line per check,
# "ok - NAME" or "not ok - NAME: why" (TAP style); a suite that exits non-zero without reporting a
# failure counts as one failed check, so a crash is never a pass.
set -u
cd "$(dirname "$0")/.."
logdir=build/tests
mkdir -p "$logdir"

echo "building the generator, the runtime and the catalogue's viewers..."
if ! make -s -j"$(nproc)" gen views >"$logdir/build.log" 2>&1; then
    tail -n 30 "$logdir/build.log"
    echo "0 passed, 1 failed"
    exit 1
fi

suites=(
    tests/unit/suite.sh       # fixed point, sine table, freestanding builds
    tests/gen/errors.sh       # malformed input: one error line, no output
    tests/gen/readers.sh      # valid files with comments, CRLF, odd headers read right; absurd headers bounded
    tests/gen/suite.sh        # determinism, chunks, budget
    tests/gen/views.sh        # --views: hidden-cell removal, frontal image unchanged
    tests/gen/budget.sh       # budgets, --fit, --emit lib, monochrome, palettes, runtime cost tables
    tests/render/suite.sh     # renders against the double-precision reference
    tests/host/suite.sh       # viewer binaries: no heap, options, interactive mode
    tests/sanitize/suite.sh   # the render and unit tests again under ASan + UBSan
    tests/fw/suite.sh         # firmware: Cortex-M3/M4 under QEMU, checksums equal the host's, budgets
    tests/stress/suite.sh     # 10^5 random views: guard zones, error bound, ASan + UBSan run
    tests/finish/suite.sh     # hole types 1-5 on synthetic images, fills and splats against a reference
    tests/accuracy/suite.sh   # the mesh reference renderer: synthetic meshes, bunny00 against its octree
)

pass=0 fail=0
for s in "${suites[@]}"; do
    [ -x "$s" ] || { echo "not ok - $s: missing or not executable"; fail=$((fail + 1)); continue; }
    log="$logdir/$(echo "$s" | tr '/' '_').log"
    "$s" >"$log" 2>&1
    status=$?
    p=$(grep -c '^ok ' "$log")
    f=$(grep -c '^not ok ' "$log")
    grep -E '^(ok|not ok) ' "$log" | sed "s|^|[$(basename "$(dirname "$s")")] |"
    if [ "$status" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "not ok - $s exited with status $status without reporting a failure (see $log)"
        tail -n 5 "$log"
        f=1
    fi
    pass=$((pass + p))
    fail=$((fail + f))
done
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
