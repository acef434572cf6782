#!/usr/bin/env bash
# The size limits on the non-test sources (app, report, io, sim, slam, eval, geometry, stats, plot,
# tools, examples, bench): no file over 350 lines and no function over 60 lines. A function's
# length is its definition's lines, from the line of its name to its closing brace, as Universal
# Ctags finds them (kind f: free and member functions, defined in a .cpp or inline in a header;
# lambdas count toward the function that holds them). Prints each breach as file:line and exits 1
# if there is one; exits 2 without ctags. A second argument checks another tree (the tests'
# fixtures).
# Usage: tools/check_sizes.sh [ROOT]
set -euo pipefail
root="${1:-$(dirname "$0")/..}"
cd "$root"
command -v ctags >/dev/null || { echo "check_sizes: no ctags (Debian: universal-ctags)" >&2; exit 2; }
dirs=()
for d in app report io sim slam eval geometry stats plot tools examples bench; do
  [ -d "$d" ] && dirs+=("$d")
done
mapfile -t files < <(find "${dirs[@]}" \( -name '*.cpp' -o -name '*.hpp' \) | sort)
status=0
# One awk over every file: its line count (wc -l's, the newlines) when the next file starts.
awk 'function check(file, lines) {
       if (lines > 350) { print file ":1: " lines " lines (the limit is 350)"; bad = 1 }
     }
     FNR == 1 && NR > 1 { check(name, count) }
     { name = FILENAME; count = FNR }
     END { if (NR > 0) check(name, count); exit bad }' "${files[@]}" || status=1
echo "check_sizes: ${#files[@]} files, none over 350 lines$([ $status -eq 0 ] || echo ': NO')"

# One ctags pass: every function's breach, then the count.
printf '%s\n' "${files[@]}" |
  ctags --languages=C++ --map-C++=+.hpp --kinds-C++=f --fields=+ne --output-format=json -o - -L - |
  python3 -c '
import json, re, sys
rows, functions = [], 0
for line in sys.stdin:
    tag = json.loads(line)
    if tag.get("_type") != "tag":
        continue
    functions += 1
    length = tag["end"] - tag["line"] + 1 if "end" in tag else 0
    if length > 60:
        scope = tag.get("scope", "")
        name = re.sub(r"__anon[0-9a-f]+", "(anonymous)", (scope + "::" if scope else "") + tag["name"])
        rows.append("%s:%d: %s is %d lines (the limit is 60)" % (tag["path"], tag["line"], name, length))
for row in sorted(rows):
    print(row)
print(f"check_sizes: {functions} functions, {len(rows)} over 60 lines")
sys.exit(1 if rows else 0)
' || status=1
exit $status
