# What tests/bench/run.sh and tests/bench/views.sh share (sourced from the repository's root).

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
