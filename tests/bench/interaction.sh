#!/usr/bin/env bash
# Interaction timing (tests/bench/interaction.c): coarse and fine frame times of bunny00 at 320x240
# and the abort latency with the poll at depth 4; appends a section to tests/bench/RESULTS.md (or to
# the file given as $1). Called by tests/bench/run.sh after its report; runs on its own too.
#   INTERACTION_RUNTIME  runtime source directory with include/ and src/ (default runtime; run.sh
#                        passes its snapshot)
set -euo pipefail
cd "$(dirname "$0")/../.."
results=${1:-tests/bench/RESULTS.md}
rt=${INTERACTION_RUNTIME:-runtime}
out=build/bench/interaction
mkdir -p "$out"
make -s build/bunny00/budget.json >/dev/null
gcc -std=c99 -O2 -g -Wall -Wextra -I"$rt/include" -I"$rt/front/host" -o "$out/interaction" tests/bench/interaction.c "$rt"/src/*.c \
    build/bunny00/*.c
# an earlier copy of this section (between its markers) is replaced, not repeated
drop_section() { [ -f "$1" ] && sed -i '/^<!-- interaction: begin -->$/,/^<!-- interaction: end -->$/d' "$1"; true; }
load0=$(cut -d' ' -f1-3 /proc/loadavg)
"$out/interaction" --frames 200 --trials 2000 --markdown >"$out/section.md"
drop_section "$results"
{
    echo "<!-- interaction: begin -->"
    cat "$out/section.md"
    echo
    echo "Load average (1, 5, 15 min) at the start: $load0; at the end: $(cut -d' ' -f1-3 /proc/loadavg) ($(nproc) cores)."
    echo "<!-- interaction: end -->"
} >>"$results"
cat "$out/section.md"
