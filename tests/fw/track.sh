#!/usr/bin/env bash
# The tracker on Cortex-M under QEMU (make firmware-track / firmware-track-run), on both boards:
# ViSP's cube (Debian visp-images-data) baked --as edges at the board's FW_TRACK_SCREEN (mps2-an386:
# 160x120; lm3s6965evb: 106x80, what its 64 KiB RAM holds) with FW_TRACK_PARTICLES (100) particles,
# and FW_TRACK_FRAMES (8) real frames of the sequence shrunk on the host into flash
# (runtime/front/fw/track_frames.py, runtime/front/fw/track_main.c):
#   - make firmware-track builds it and check_elf.py's checks pass (passed through here): no heap
#     symbols, the model's arrays, buffers and the stored frames of exactly budget.json's sizes, flash
#     and RAM within the stated margins, fits the board, static stack bound within the reservation;
#     and it is baked as asked (budget.json's screen and particles)
#   - make firmware-track-run: QEMU runs it to "done" with exit status 0, one "pose" line a frame,
#     byte for byte the host tracker's --fixed-out lines (build/fw/B-track/cube/cube-track, the same
#     bake, on the same stored frames as PGM files with --shrunk K, the same camera, start pose,
#     settings and seed): the fixed-point tracker is bit-exact across architectures
#   - the stored frames are the host tracker's own shrinking: the host tracker on the original
#     640x480 frames (shrunk by itself) writes the same pose lines
#   - the poses are a tracking, not noise: every frame's estimate matches at least 90 % of its
#     visible line pixels, the translations stay within 5 cm of the start pose
#   - the measured stack high-water mark is below the static bound
# and on mps2-an386 the instructions (make bench-firmware-track: -icount shift=0) per frame and per
# particle, as an info line. Skips (with the reason) only when qemu-system-arm or arm-none-eabi-gcc is
# missing. Prints one line per check, "ok - fw: track: ..." or "not ok - fw: track: ...: why".
set -u
cd "$(dirname "$0")/../.." || exit 1
TAP_PREFIX="fw: track: "
. tests/lib.sh
# the firmware's compiles through the shared object cache (tests/cc_cached.sh): the runtime's
# objects are the same for a board's points, mesh and tracker firmware, and are compiled once
arm_cc="ARM_CC=tests/cc_cached.sh arm-none-eabi-gcc"
out=build/tests/fw-track
fresh_dir "$out"
check() { check_problems "$@"; }
mbt=/usr/share/visp-images-data/ViSP-images/mbt
t0=$(date +%s)

missing=""
for t in qemu-system-arm arm-none-eabi-gcc; do command -v "$t" >/dev/null || missing="$missing $t"; done
if [ -n "$missing" ]; then
    skip "the tracker firmware under QEMU" "missing:$missing (make deps installs gcc-arm-none-eabi and qemu-system-arm)"
    exit 0
fi
if [ ! -f "$mbt/cube.cao" ]; then
    notok "ViSP's cube" "$mbt/cube.cao missing: make deps installs visp-images-data"
    exit 1
fi

for b in mps2-an386 lm3s6965evb; do
    dir=build/fw/$b-track
    elf=$dir/cube-track.elf
    # ---- build and the post-link checks ----------------------------------------------------------
    rm -f "$elf"
    make -s --no-print-directory "$arm_cc" firmware-track BOARD=$b >"$out/$b.build.txt" 2>&1
    st=$?
    grep -E '^(ok|not ok) - fw: ' "$out/$b.build.txt" | sed "s/^\(ok\|not ok\) - fw: /\1 - fw: track: $b: /"
    grep -q '^not ok' "$out/$b.build.txt" && status=1
    if [ $st -ne 0 ] || [ ! -f "$elf" ]; then
        notok "$b: make firmware-track BOARD=$b" "exit $st: $(grep -v '^ok' "$out/$b.build.txt" | tail -5 | oneline)"
        continue
    fi
    ok "$b: make firmware-track BOARD=$b builds $elf"
    screen=$(mkvar FW_TRACK_SCREEN BOARD=$b)
    particles=$(mkvar FW_TRACK_PARTICLES BOARD=$b)
    frames=$(mkvar FW_TRACK_FRAMES BOARD=$b)
    read -r got_screen got_particles < <(python3 -c 'import json,sys; b=json.load(open(sys.argv[1])); print("%dx%d" % tuple(b["screen"]), b["ram"]["particle_count"])' "$dir/cube/budget.json")
    check "$b: baked as the board asks: --screen $screen --particles $particles" \
        "$([ "$got_screen $got_particles" = "$screen $particles" ] || echo "budget.json says screen $got_screen, $got_particles particles")"

    # ---- run under QEMU, compare with the host ----------------------------------------------------
    start=$(date +%s)
    make -s --no-print-directory "$arm_cc" firmware-track-run BOARD=$b FW_QEMU_TIMEOUT=120 >"$out/$b.run.txt" 2>&1
    st=$?
    secs=$(($(date +%s) - start))
    run=$dir/run.txt
    check "$b: make firmware-track-run: QEMU runs the tracker to \"done\", exit status 0 ($secs s with the host's run)" \
        "$([ $st -eq 0 ] && grep -q '^done' "$run" 2>/dev/null || echo "exit $st: $(tail -5 "$out/$b.run.txt" | oneline)")"
    grep '^pose ' "$run" >"$out/$b.fw-poses.txt" 2>/dev/null
    cp "$dir/host-poses.txt" "$out/$b.host-poses.txt" 2>/dev/null
    nfw=$(wc -l <"$out/$b.fw-poses.txt")
    check "$b: the firmware prints $frames pose lines and the host tracker's --fixed-out $frames" \
        "$([ "$nfw" -eq "$frames" ] && [ "$(wc -l <"$out/$b.host-poses.txt" 2>/dev/null)" = "$frames" ] || echo "firmware $nfw lines, host $(wc -l <"$out/$b.host-poses.txt" 2>/dev/null) lines")"
    check "$b: all $frames poses (Q30 quaternion, um, visible, matched, confidence) equal the host tracker's, byte for byte" \
        "$([ "$nfw" -gt 0 ] && cmp -s "$out/$b.fw-poses.txt" "$out/$b.host-poses.txt" && grep -q "^firmware-track-run: all $frames poses equal the host's" "$out/$b.run.txt" ||
            diff "$out/$b.fw-poses.txt" "$out/$b.host-poses.txt" 2>&1 | head -4 | oneline)"

    # the stored frames are what the host tracker's own shrinking gives: the same poses from the originals
    # shellcheck disable=SC2046
    "$dir/cube/cube-track" $(sed '/^--frames$/,+1d; /^--shrunk$/,+1d' "$dir/frames/host-args") \
        --frames "$mbt/cube/image%04d.pgm" --fixed-out "$out/$b.orig-poses.txt" >/dev/null 2>"$out/$b.orig.err"
    st=$?
    check "$b: the host tracker on the original 640x480 frames (shrunk by itself) gives the same poses as on the stored frames" \
        "$([ $st -eq 0 ] && cmp -s "$out/$b.orig-poses.txt" "$out/$b.host-poses.txt" ||
            echo "exit $st: $(cat "$out/$b.orig.err") $(diff "$out/$b.orig-poses.txt" "$out/$b.host-poses.txt" 2>&1 | head -2)" | oneline)"

    # a tracking: matched / visible >= 0.9 in every frame, translations within 5 cm of the start
    why=$(python3 - "$out/$b.fw-poses.txt" "$mbt/cube.0.pos" <<'EOF'
import sys
start = [float(w) * 1e6 for w in open(sys.argv[2]).read().split()[:3]]
bad = []
for line in open(sys.argv[1]):
    f = line.split()
    k, t, vis, mat = int(f[1]), [int(x) for x in f[6:9]], int(f[9]), int(f[10])
    if vis == 0 or mat < 0.9 * vis:
        bad.append(f"frame {k}: {mat} of {vis} matched")
    d = max(abs(a - b) for a, b in zip(t, start))
    if d > 50000:
        bad.append(f"frame {k}: {d / 1000:.0f} mm from the start")
print("; ".join(bad[:4]))
EOF
)
    check "$b: every frame's estimate matches >= 90 % of its visible line pixels, within 5 cm of the start pose" "$why"

    used=$(sed -n 's/^stack used \([0-9]*\) of.*/\1/p' "$run")
    bound=$(sed -n 's/^# .*stack bound \([0-9]*\) bytes.*/\1/p' "$out/$b.build.txt" | head -1)
    check "$b: measured stack high-water mark (${used:-?} bytes) is within the static bound (${bound:-?} bytes)" \
        "$([ -n "$used" ] && [ -n "$bound" ] && [ "$used" -gt 0 ] && [ "$used" -le "$bound" ] || echo "used '${used}' bound '${bound}'")"
done

# ---- instructions on the Cortex-M4 --------------------------------------------------------------------
# (its section goes to a file of the test's own: tests/bench/RESULTS.md is written by benchmark runs)
: >"$out/RESULTS.md"
tests/fw/track_bench.sh "$out/RESULTS.md" >"$out/bench.txt" 2>&1
st=$?
line=$(grep '^per frame: ' "$out/bench.txt")
check "mps2-an386: the bench-firmware-track script counts instructions under -icount shift=0, poses equal the host's" \
    "$([ $st -eq 0 ] && [ -n "$line" ] || echo "exit $st: $(tail -3 "$out/bench.txt" | oneline)")"
[ -n "$line" ] && echo "# fw: track: Cortex-M4 instructions (mps2-an386, $(mkvar FW_TRACK_SCREEN BOARD=mps2-an386), $(mkvar FW_TRACK_PARTICLES) particles): $line"
echo "# fw: track: $(($(date +%s) - t0)) s"
exit $status
