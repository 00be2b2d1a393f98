# Shared by the test suites (sourced after they cd to the top of the checkout): one line per check,
# "ok - PREFIX NAME" or "not ok - PREFIX NAME: why", which tests/run.sh counts. Set TAP_PREFIX
# (for example "fw: ") before sourcing. A failure sets status=1 and counts in fails; a suite exits
# with either.
# shellcheck shell=bash
status=0
fails=0
ok() { echo "ok - ${TAP_PREFIX:-}$1"; }
notok() { echo "not ok - ${TAP_PREFIX:-}$1${2:+: $2}"; status=1; fails=$((fails + 1)); }   # NAME [WHY]
check_problems() { if [ -z "$2" ]; then ok "$1"; else notok "$1" "$2"; fi; }   # NAME PROBLEMS: ok when empty
check_cmd() { local name=$1; shift; if "$@"; then ok "$name"; else notok "$name"; fi; }   # NAME COMMAND...
oneline() { tr '\n' ' ' | sed 's/  */ /g; s/ $//' | cut -c1-400; }   # a log excerpt as one short line
