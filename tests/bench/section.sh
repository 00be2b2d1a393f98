# Sourced by the benchmark scripts: replaces one marked section of RESULTS.md.
#   write_section RESULTS NAME SECTION_FILE COMMAND...
# deletes the lines from "<!-- NAME: begin -->" to "<!-- NAME: end -->", appends the section file, then
# the commands that produced it (one per argument), between the same markers; prints the section.
write_section() {
    local results=$1 name=$2 file=$3
    shift 3
    sed -i "/^<!-- $name: begin -->\$/,/^<!-- $name: end -->\$/d" "$results"
    {
        echo "<!-- $name: begin -->"
        cat "$file"
        echo
        echo "Commands:"
        echo
        echo '```'
        printf '%s\n' "$@"
        echo '```'
        echo "<!-- $name: end -->"
    } >>"$results"
    cat "$file"
}
