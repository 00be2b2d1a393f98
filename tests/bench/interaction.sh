#!/usr/bin/env bash
# Interaction timing (tests/bench/interaction.c): coarse and fine frame times of bunny00 at 320x240
# and the abort latency with the poll at depth 4; writes its section of tests/bench/RESULTS.md (or of
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
. tests/bench/section.sh
cmds=()
run() { cmds+=("$*"); "$@"; }
run gcc -std=c99 -O2 -g -Wall -Wextra -I"$rt/include" -I"$rt/front/host" -o "$out/interaction" tests/bench/interaction.c "$rt"/src/*.c \
    build/bunny00/*.c
load0=$(cut -d' ' -f1-3 /proc/loadavg)
cmds+=("$out/interaction --frames 200 --trials 2000 --markdown")
"$out/interaction" --frames 200 --trials 2000 --markdown >"$out/section.md"
{
    cat "$out/section.md"
    echo
    echo "Load average (1, 5, 15 min) at the start: $load0; at the end: $(cut -d' ' -f1-3 /proc/loadavg) ($(nproc) cores)."
} >"$out/section.full.md"
write_section "$results" interaction "$out/section.full.md" "${cmds[@]}" >/dev/null
cat "$out/section.md"
