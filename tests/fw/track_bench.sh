#!/usr/bin/env bash
# make bench-firmware-track: the tracker firmware (runtime/front/fw/track_main.c) on mps2-an386
# (Cortex-M4) under qemu-system-arm -icount shift=0, whose instruction counts do not drift: per frame,
# the edge stage (the stored frame, mc_imgedge, the masks) and the filter step, per particle, and
# whether the poses equal the host tracker's on the same frames. Writes a marked section of
# tests/bench/RESULTS.md.
#   tests/fw/track_bench.sh [RESULTS.md]
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
out=build/fw/mps2-an386-track
mkdir -p "$out"
make -s --no-print-directory fw-bench-firmware-track >"$out/bench-table.txt"
sec=$out/section.md
{
    echo "## Tracking on a Cortex-M4 under QEMU"
    echo
    echo "\`tests/fw/track_bench.sh\` (\`make bench-firmware-track\`): the tracker firmware on mps2-an386 tracking 8 frames of ViSP's real cube sequence (\`runtime/front/fw/track_frames.py\` shrinks them on the host to the bake's --screen; the host tracker runs the same frames and must give the same poses). Instructions counted through SysTick under \`qemu-system-arm -icount shift=0\` (counter.h): edges = copying the stored frame, \`mc_imgedge\` and \`mc_imgedge_masks\`; filter = \`mc_filter_step\` (N + 1 scores)."
    echo
    echo '```'
    cat "$out/bench-table.txt"
    echo '```'
} >"$sec"
write_section "$results" bench-firmware-track "$sec" "make -s fw-bench-firmware-track   # firmware-track + fw-track-host + fw-track-bench, BOARD=mps2-an386"
