# What the benchmark scripts share (sourced from the repository's root): run.sh, views.sh, web.sh,
# and the tracker's track.sh and line_select.sh.

# The compiler settings: the Makefile's, without -Werror, so that a benchmark measures what `make`
# builds.
CC=${CC:-gcc}
[ "$CC" = cc ] && CC=gcc
OPT="-O2 -g"                                       # the Makefile's CFLAGS
RT_FLAGS="-std=c99 -ffreestanding -Wall -Wextra"   # the Makefile's RT_CFLAGS
HOST_FLAGS="-std=c99 -Wall -Wextra"                # the Makefile's HOST_CFLAGS

# bench_quote ARGS...: the command as one shell-quoted line, for the Commands list of RESULTS.md
bench_quote() {
    local a q=""
    for a in "$@"; do
        if [[ $a =~ ^[][A-Za-z0-9_./=,:+@%-]+$ ]]; then q+="$a "; else q+="$(printf '%q' "$a") "; fi
    done
    printf '%s' "${q% }"
}

# The tracker's filter benchmark program (tests/bench/track_frames.c) with the runtime sources it
# runs: the compile line, for track.sh and line_select.sh (extra flags before OUT's -o).
#   track_frames_cc OUT [FLAGS...]
track_frames_cc() {
    local prog=$1
    shift
    echo "$CC" $OPT -std=c99 -D_POSIX_C_SOURCE=200809L -Wall -Wextra "$@" -Iruntime/include -Iruntime/front/host -o "$prog" \
        tests/bench/track_frames.c runtime/src/particles.c runtime/src/detect.c runtime/src/track.c runtime/src/camera.c \
        runtime/src/sdepth.c runtime/src/line.c runtime/src/raster.c runtime/src/imgedge.c runtime/src/target.c -lm
}
