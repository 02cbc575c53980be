#!/usr/bin/env bash
# How large the recipes are: the number of dimension branches (`if constexpr (D == 2)`) in engine/ and systems/, and
# the longest functions of engine/methods (Universal Ctags' start and end lines), at the working tree or at a
# revision -- the before/after figures of a reorganisation.
#
#   tools/recipe_size.sh [REV] [N]     (default: the working tree; the N = 10 longest functions)
set -euo pipefail
rev="${1:-}"
top="${2:-10}"
root="$(git rev-parse --show-toplevel)"
dir="$root"
if [[ -n "$rev" ]]; then
  dir="$(mktemp -d)"
  trap 'rm -rf "$dir"' EXIT
  git -C "$root" archive "$rev" engine systems | tar -x -C "$dir"
fi
cd "$dir"
branches=$(grep -rho "constexpr (D == 2)" engine systems | wc -l)
echo "D-branches (if constexpr (D == 2)) in engine/ and systems/: $branches"
echo "longest functions of engine/methods (lines, file:line, name):"
ctags --output-format=json --fields=+ne --kinds-c++=f -R -f - engine/methods |
  python3 -c '
import json, sys
rows = []
for line in sys.stdin:
    t = json.loads(line)
    if "end" in t:
        name = (t["scope"] + "::" if t.get("scope") else "") + t["name"]
        rows.append((t["end"] - t["line"] + 1, "%s:%d" % (t["path"], t["line"]), name.replace("loom::", "").removeprefix("loom::")))
rows.sort(key=lambda r: (-r[0], r[1]))
for n, where, name in rows[:int(sys.argv[1])]:
    print("%5d  %s  %s" % (n, where, name))
' "$top"
