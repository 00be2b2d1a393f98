#!/usr/bin/env bash
# The tracker's particle filter: run time and error on the synthetic cube sequence
# (tests/track/cube_scene.h: ViSP's 84 mm cube before ViSP's cube camera scaled to the frame, each
# frame's edges those of the cube's visible lines at the true pose, spread by a pixel; no clutter,
# no noise: the real and cluttered sequences beside ViSP's tracker are track_seq.sh's). For each frame
# size and particle count (a third of them fresh each frame, as the paper's 100 of 300), in 6-DOF
# and 3-DOF (orientation given): tests/bench/track_frames.c runs 60 frames from a start 15 mm off;
# wall ms of mc_filter_step per frame (median over frames, then over rounds), the pose errors
# against the truth (medians) and the frames within 5 mm and 3 degrees and within 5 cm and 5
# degrees; instructions: callgrind, mc_filter_step alone, 20 frames, per frame and per particle
# (scores: particles + 1 a frame). Writes a marked section of RESULTS.md.
#   tests/bench/track.sh [RESULTS.md]      (make bench runs it; make bench-track alone)
#   TRACK_SIZES ("320x180 640x360"), TRACK_PARTICLES ("100 300 1000"), TRACK_ROUNDS (5)
set -euo pipefail
cd "$(dirname "$0")/../.."
. tests/bench/common.sh
. tests/bench/section.sh
results=${1:-tests/bench/RESULTS.md}
sizes=${TRACK_SIZES:-320x180 640x360} counts=${TRACK_PARTICLES:-100 300 1000} rounds=${TRACK_ROUNDS:-5}
out=build/bench/track
mkdir -p "$out"
cmds=()
run() { cmds+=("$*"); "$@"; }
prog=$out/track_frames
# shellcheck disable=SC2046
run $(track_frames_cc "$prog")
val() { sed -n "s/^$1 //p" "$2"; }
rows=$out/rows.txt
: >"$rows"
for size in $sizes; do
    for n in $counts; do
        fresh=$((n / 3))
        for dof in 6 3; do
            args=(--particles "$n" --fresh "$fresh" --size "$size" --dof "$dof")
            stem=$out/$size-$n-$dof
            : >"$stem.ms"
            for r in $(seq 1 "$rounds"); do
                "$prog" "${args[@]}" >"$stem.r$r.txt"
                val "ms per frame (median)" "$stem.r$r.txt" >>"$stem.ms"
            done
            ms=$(sort -g "$stem.ms" | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}')
            run valgrind --tool=callgrind --toggle-collect=mc_filter_step --callgrind-out-file="$stem.cg" \
                "$prog" "${args[@]}" --frames 20 >"$stem.cg.txt" 2>"$stem.cg.log"
            ir=$(callgrind_annotate "$stem.cg" 2>/dev/null | awk '/PROGRAM TOTALS/ && !done {gsub(",", "", $1); print $1; done = 1}')
            r1=$stem.r1.txt
            printf '| %s | %s | %s | %s | %.3f | %.2f M | %s | %s | %s | %s of 60 | %s of 60 |\n' "$size" "$n" "$fresh" "$dof" "$ms" \
                "$(echo "$ir / 20 / 1000000" | bc -l)" "$(printf '%.0f' "$(echo "$ir / 20 / ($n + 1)" | bc -l)")" \
                "$(val "translation error mm (median)" "$r1")" "$(val "rotation error deg (median)" "$r1")" \
                "$(val "frames within 5 mm and 3 deg" "$r1")" "$(val "frames within 5 cm and 5 deg" "$r1")" >>"$rows"
        done
    done
done
cmds+=("$prog --particles N --fresh N/3 --size WxH --dof D   # per row, $rounds rounds")
sec=$out/section.md
{
    echo "## Tracking: the particle filter on a synthetic cube sequence"
    echo
    echo "\`tests/bench/track.sh\` (\`make bench-track\`): the synthetic cube sequence of \`tests/track/cube_scene.h\` (ViSP's 84 mm cube from its mbt/cube model, before ViSP's cube camera scaled to the frame; each frame's edges are the cube's own visible lines at the true pose, spread by a pixel: no clutter and no noise, so the errors are the filter's, not the image's), turning 0.01 rad and drifting about 1.5 mm a frame, the filter started 15 mm off; N particles, N/3 of them fresh a frame, in one layer as the paper has it: without the later layers' recall term the tracker does not use its image search (detect.h, particles.h), so the fresh particles are the paper's. Per row, \`tests/bench/track_frames.c\` runs 60 frames: ms = wall time of \`mc_filter_step\` per frame (the frame's edges made before, untimed), median over frames, then over $rounds rounds; Ir = callgrind instructions of \`mc_filter_step\` (every particle's motion and score, the estimate's score), per frame and per scored pose (particles + 1), 20 frames; errors: the estimate against the truth, medians over the 60 frames; the frames within 5 mm and 3 degrees, and within the issue's 5 cm and 5 degrees. 3-DOF: the orientation is given each frame (the paper's IMU). gcc -O2, $(gcc --version | head -n 1)."
    echo
    echo "| frame | particles | fresh | DOF | ms per frame | Ir per frame | Ir per pose | translation error mm | rotation error deg | within 5 mm, 3 deg | within 5 cm, 5 deg |"
    echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    cat "$rows"
    echo
    echo "Load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)."
} >"$sec"
write_section "$results" track "$sec" "${cmds[@]}"
