#!/usr/bin/env python3
"""Checks the choice lists in the scene examples of the documentation against the schema (called by
tests/tools/readme_commands.sh). Usage: readme_choices.py SCHEMA_MARKDOWN FILE...

SCHEMA_MARKDOWN is the output of `loom schema --markdown`. In every fenced block of FILE marked `toml` or not
marked, a line `key = "value"   # a | b | c` whose comment starts with a choice followed by `|` lists choices; each
choice may be followed by a remark in parentheses, `newmark (mpm: ...)`. The key is resolved against the block's
table headers (`[time]` + `integrator` is time.integrator, `[[probe]]` + `kind` is probe[].kind) and the choices
must be exactly the key's "one of ..." in the schema, in any order. Prints one line per list (`ok` or `FAILED`,
FILE:LINE) and exits 1 if any list differs or cannot be read.
"""
import re
import sys

CHOICE = r"[A-Za-z0-9_.]+"
REMARK = r"\([^()]*(?:\([^()]*\)[^()]*)*\)"  # one level of nested parentheses
ITEM = re.compile(rf'^\s*"?({CHOICE})"?\s*(?:{REMARK}\s*)*$')
LIST_START = re.compile(rf'^\s*"?{CHOICE}"?\s*(?:{REMARK}\s*)*\|')
ASSIGN = re.compile(r'^\s*([A-Za-z0-9_.]+)\s*=\s*"[^"]*"\s*#(.*)$')
HEADER = re.compile(r"^\s*(\[\[?)\s*([A-Za-z0-9_.]+)\s*\]\]?\s*(#.*)?$")


def one_of_lists(schema_markdown):
    lists = {}
    for line in schema_markdown.splitlines():
        m = re.match(r"^\| `([^`]+)` \| one of ([^|]+) \|", line)
        if m:
            lists[m.group(1)] = [c.strip() for c in m.group(2).split(",")]
    return lists


def check(path, lists):
    failed = checked = 0
    fence = None  # the info string of the open fence, or None outside one
    prefix = ""
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            stripped = line.strip()
            if stripped.startswith("```"):
                fence = None if fence is not None else stripped[3:].strip()
                prefix = ""
                continue
            if fence not in ("toml", ""):
                continue
            header = HEADER.match(line)
            if header:
                prefix = header.group(2) + ("[]." if header.group(1) == "[[" else ".")
                continue
            assign = ASSIGN.match(line)
            if not assign or not LIST_START.match(assign.group(2)):
                continue
            key, comment = prefix + assign.group(1), assign.group(2)
            checked += 1
            where = f"{path}:{number}"
            items = [ITEM.match(part) for part in comment.split("|")]
            if not all(items):
                print(f"FAILED {where}: cannot read the choice list of {key}: #{comment}")
                failed += 1
                continue
            listed = [m.group(1) for m in items]
            if key not in lists:
                print(f"FAILED {where}: {key} lists choices, but the schema gives {key} no 'one of' list")
                failed += 1
                continue
            missing = [c for c in lists[key] if c not in listed]
            unknown = [c for c in listed if c not in lists[key]]
            doubled = sorted({c for c in listed if listed.count(c) > 1})
            if missing or unknown or doubled:
                what = "; ".join(s for s in (
                    "missing " + ", ".join(missing) if missing else "",
                    "not in the schema " + ", ".join(unknown) if unknown else "",
                    "listed twice " + ", ".join(doubled) if doubled else "") if s)
                print(f"FAILED {where}: the choices of {key} differ from the schema's one of "
                      f"{', '.join(lists[key])}: {what}")
                failed += 1
            else:
                print(f"ok   {where} (the choices of {key} are the schema's)")
    return checked, failed


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    with open(sys.argv[1], encoding="utf-8") as f:
        lists = one_of_lists(f.read())
    if "scene.method" not in lists:
        sys.exit(f"{sys.argv[1]}: no 'one of' list for scene.method: not the output of loom schema --markdown")
    checked = failed = 0
    for path in sys.argv[2:]:
        c, f_ = check(path, lists)
        checked += c
        failed += f_
    if checked == 0:
        print("no choice list found in the scene examples: the extraction is broken")
        return 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
