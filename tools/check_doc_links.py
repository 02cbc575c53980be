#!/usr/bin/env python3
"""Checks the relative links of Markdown pages: every link's file exists and every #anchor is a heading of the
target page, as GitHub spells it (lower case, punctuation dropped, spaces to hyphens, -1, -2 for repeats).
Inline links [text](target) and reference definitions [label]: target are read, outside code blocks and spans;
links to web addresses are not followed.
Usage: tools/check_doc_links.py [FILE...]   (default: README.md and docs/guide/*.md). Exit 1 on a broken link.
"""
import os
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def prose_lines(text, blank_code=True):
    """(line number, line) outside fenced and indented code blocks, code spans blanked unless asked not to."""
    fence = None
    for number, line in enumerate(text.split("\n"), 1):
        stripped = line.lstrip()
        if stripped.startswith("```") or stripped.startswith("~~~"):
            marker = stripped[:3]
            fence = None if fence == marker else (fence or marker)
            continue
        if fence or line.startswith("    ") or line.startswith("\t"):
            continue
        yield number, re.sub(r"(`+).*?\1", "", line) if blank_code else line


def slug(heading):
    heading = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link's text
    heading = heading.replace("`", "").replace("*", "")
    heading = heading.strip().lower()
    heading = re.sub(r"[^\w\- ]", "", heading)
    return heading.replace(" ", "-")


def anchors(path, cache={}):
    if path not in cache:
        seen, result = {}, set()
        for _, line in prose_lines(path.read_text(encoding="utf-8"), blank_code=False):
            m = re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
            if not m:
                continue
            base = slug(m.group(2))
            n = seen.get(base, 0)
            seen[base] = n + 1
            result.add(base if n == 0 else f"{base}-{n}")
        for m in re.finditer(r'<a\s+(?:name|id)="([^"]+)"', path.read_text(encoding="utf-8")):
            result.add(m.group(1))
        cache[path] = result
    return cache[path]


def links(text):
    for number, line in prose_lines(text):
        for m in re.finditer(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)", line):
            yield number, m.group(1)
        m = re.match(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+\"[^\"]*\")?\s*$", line)
        if m:
            yield number, m.group(1)


def check(page):
    errors = 0
    for number, target in links(page.read_text(encoding="utf-8")):
        if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:
            continue
        path, _, anchor = target.partition("#")
        dest = (page.parent / path).resolve() if path else page
        where = f"{os.path.relpath(page)}:{number}"
        if not dest.exists():
            print(f"{where}: {target}: no such file")
            errors += 1
        elif anchor and dest.suffix == ".md" and anchor not in anchors(dest):
            print(f"{where}: {target}: no heading #{anchor} in {os.path.relpath(dest)}")
            errors += 1
        elif anchor and dest.is_dir():
            print(f"{where}: {target}: an anchor on a directory")
            errors += 1
    return errors


def main():
    pages = [Path(a).resolve() for a in sys.argv[1:]] or [ROOT / "README.md", *sorted((ROOT / "docs/guide").glob("*.md"))]
    errors = sum(check(p) for p in pages)
    count = sum(1 for p in pages for _ in links(p.read_text(encoding="utf-8")))
    print(f"check_doc_links: {len(pages)} pages, {count} links, {errors} broken")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
