# One line per check, which tests/run.sh counts (sourced by tests/lib.sh; a suite sources that):
#   ok - PREFIX NAME              passed
#   not ok - PREFIX NAME: why     failed: sets status=1 and counts in fails; a suite exits with either
#   ok - PREFIX NAME # SKIP why   not run (TAP's directive): counted as skipped, never as passed
# Set TAP_PREFIX (for example "fw: ") before sourcing.
# shellcheck shell=bash
status=0
fails=0
ok() { echo "ok - ${TAP_PREFIX:-}$1"; }
notok() { echo "not ok - ${TAP_PREFIX:-}$1${2:+: $2}"; status=1; fails=$((fails + 1)); }   # NAME [WHY]
skip() { echo "ok - ${TAP_PREFIX:-}$1 # SKIP ${2:-no reason given}"; }   # NAME WHY
check_problems() { if [ -z "$2" ]; then ok "$1"; else notok "$1" "$2"; fi; }   # NAME PROBLEMS: ok when empty
check_cmd() { local name=$1; shift; if "$@"; then ok "$name"; else notok "$name"; fi; }   # NAME COMMAND...
oneline() { tr '\n' ' ' | sed 's/  */ /g; s/ $//' | cut -c1-400; }   # a log excerpt as one short line
