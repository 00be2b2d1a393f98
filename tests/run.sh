#!/usr/bin/env bash
# The whole test suite (make test). Builds what the tests need, runs every suite, prints each
# suite's checks, counts and time, and ends with exactly one line "N passed, N failed, N skipped".
# A suite prints one line per check (tests/tap.sh): "ok - NAME" (passed), "not ok - NAME: why"
# (failed) or "ok - NAME # SKIP why" (skipped: counted apart, never as a pass). A suite that exits
# non-zero without reporting a failure counts as one failed check, so a crash is never a pass.
# Exits non-zero when anything failed. With arguments (tests/run.sh tests/gen/suite.sh ...), runs only
# those suites.
set -u
cd "$(dirname "$0")/.."
# Debian's programs first, as the Makefile has them (run.sh may be started without make)
case ":$PATH:" in :/usr/bin:/bin:*) ;; *) export PATH=/usr/bin:/bin:$PATH ;; esac
logdir=build/tests
mkdir -p "$logdir"
# a suite is reported once its status file appears: none may be left from an earlier run
rm -f "$logdir"/*.log.status "$logdir"/*.log.status.tmp

echo "building the generator, the runtime, the catalogue's viewers and the cube's tracker..."
if ! make -s -j"$(nproc)" gen views build/cube/cube-track >"$logdir/build.log" 2>&1; then
    tail -n 30 "$logdir/build.log"
    echo "0 passed, 1 failed, 0 skipped"
    exit 1
fi

# longest first (CPU seconds in tests/README.md), so that the two job slots finish together
suites=(
    tests/unit/suite.sh       # fixed point, sine table, ... under ASan + UBSan; freestanding builds
    tests/fw/suite.sh         # firmware: Cortex-M3/M4 under QEMU, checksums equal the host's, budgets
    tests/gen/pmesh.sh        # the progressive mesh: every level valid, levels equal OpenMesh's decimation
    tests/fw/stream.sh        # the stream receiver firmware over the UART under QEMU: levels' checksums equal the host's
    tests/points/suite.sh     # sparse point sets filled at bake time: closed surfaces, under 2 % background or far side
    tests/stress/suite.sh     # 2x10^4 random views: guard zones, error bound, ASan + UBSan run
    tests/gen/gltf.sh         # glTF input: meshes as .gltf/.glb read and bake as their OFF twins, Debian's samples, malformed files
    tests/stream/suite.sh     # streamed bakes: every prefix draws its level exactly, damaged streams refused
    tests/gen/budget.sh       # budgets, --fit, --emit lib, monochrome, palettes, runtime cost tables
    tests/render/suite.sh     # renders against the double-precision reference
    tests/gen/qi.sh           # hidden lines by quantitative invisibility: exact in integers, a double reference
    tests/gen/suite.sh        # determinism, chunks, budget
    tests/host/suite.sh       # viewer binaries: no heap, options, interactive mode
    tests/stream/host.sh      # the host viewer's --stream from a pipe, a FIFO, TCP: cuts and damage keep the last good level
    tests/web/suite.sh        # the web viewer in headless Chromium: frames equal the native viewer's
    tests/sanitize/suite.sh   # the render tests and a viewer again under ASan + UBSan
    tests/gen/views.sh        # --views: hidden-cell removal, frontal image unchanged
    tests/track/suite.sh      # edge-model bakes against the source, the tracker on synthetic and real sequences
    tests/web/stream.sh       # the web page over a streaming fetch in headless Chromium: cuts, damage, progressive frames
    tests/gen/clip.sh         # near-plane and guard-band clipping in whole frames: eye inside, magnified, random views
    tests/finish/suite.sh     # hole types 1-5 on synthetic images, fills and splats against a reference
    tests/fw/track.sh         # the tracker firmware under QEMU: ViSP's cube, poses equal the host tracker's
    tests/accuracy/suite.sh   # the mesh reference renderer: synthetic meshes, bunny00 against its octree
    tests/gen/errors.sh       # malformed input: one error line, no output
    tests/gen/readers.sh      # valid files with comments, CRLF, odd headers read right; absurd headers bounded
    tests/fuzz/suite.sh       # the fuzzers' findings (tests/fuzz/regress/) replayed through modelc
)

[ $# -eq 0 ] || suites=("$@")   # tests/run.sh SUITE...: only those
skip_re='^ok .*# *[Ss][Kk][Ii][Pp]'
# TEST_JOBS suites run at once (default 2: most suites use one core, and each writes only its own
# directories under build/); TEST_JOBS=1 runs them one after another. Each suite's block is printed
# in the order above as soon as it and those before it are done.
jobs_max=${TEST_JOBS:-2}
log_of() { echo "$logdir/$(echo "$1" | tr '/' '_').log"; }
start() {   # runs suite $1 in the background: its log, wall and CPU time, exit status
    local s=$1 log
    log=$(log_of "$s")
    rm -f "$log.status"
    (
        TIMEFORMAT='%R %U %S'
        if [ -x "$s" ]; then
            { time "$s" >"$log" 2>&1; } 2>"$log.time"
            echo $? >"$log.status.tmp"
        else
            echo "not ok - $s: missing or not executable" >"$log"
            echo "0 0 0" >"$log.time"
            echo 1 >"$log.status.tmp"
        fi
        mv "$log.status.tmp" "$log.status"
    ) &
}
pass=0 fail=0 skip=0 times=() next=0
report() {   # prints the finished suites, in order, up to the first unfinished one
    local s label log status wall user sys p f k cpu line
    while [ "$next" -lt "${#suites[@]}" ]; do
        s=${suites[$next]}
        log=$(log_of "$s")
        [ -f "$log.status" ] || return 0
        next=$((next + 1))
        label=${s#tests/}
        label=${label%.sh}
        label=${label%/suite}
        status=$(cat "$log.status")
        read -r wall user sys < <(tail -n 1 "$log.time")
        grep -E '^(ok|not ok) ' "$log" | sed "s|^|[$label] |"
        p=$(grep -E '^ok ' "$log" | grep -cvE "$skip_re")
        k=$(grep -cE "$skip_re" "$log")
        f=$(grep -c '^not ok ' "$log")
        if [ "$status" -ne 0 ] && [ "$f" -eq 0 ]; then
            echo "not ok - $s exited with status $status without reporting a failure (see $log)"
            tail -n 5 "$log" | sed 's/^/#   /'
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
}
t0=$(date +%s)
for s in "${suites[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$jobs_max" ]; do
        wait -n
        report
    done
    start "$s"
done
while [ "$next" -lt "${#suites[@]}" ]; do
    wait -n 2>/dev/null || sleep 1
    report
done
echo "times ($jobs_max at once, $(($(date +%s) - t0)) s in all):"
printf '  %s\n' "${times[@]}"
echo "$pass passed, $fail failed, $skip skipped"
[ "$fail" -eq 0 ]
