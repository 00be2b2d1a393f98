# Sourced by the benchmark scripts: replaces one marked section of RESULTS.md.
#   write_section RESULTS NAME SECTION_FILE COMMAND...
# replaces the lines from "<!-- NAME: begin -->" to "<!-- NAME: end -->" where they stand (a new
# section is appended) with the section file, then the commands that produced it (one per argument),
# between the same markers; prints the section. The file is rewritten through a temporary beside it.
write_section() {
    local results=$1 name=$2 file=$3 block
    shift 3
    block=$(mktemp "$results.XXXXXX")
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
    } >"$block"
    awk -v b="<!-- $name: begin -->" -v e="<!-- $name: end -->" -v blk="$block" '
        function put(   l) { while ((getline l < blk) > 0) print l; close(blk); done = 1 }
        $0 == b { skip = 1; put(); next }
        skip { if ($0 == e) skip = 0; next }
        { print }
        END { if (!done) put() }' "$results" >"$block.new" && mv "$block.new" "$results"
    rm -f "$block"
    cat "$file"
}
