#!/usr/bin/env python3
"""Checks the relative links of the docs: every linked file exists and every #anchor names a
heading of the linked page (GitHub's slugs). Usage: check_doc_links.py [ROOT]; prints each
broken link and exits 1 if there is one."""
import glob
import os
import re
import sys


def slug(title):
    title = re.sub(r"[^a-z0-9 \-_]", "", title.strip().lower())
    return title.replace(" ", "-")


def headings(path):
    found, in_code = set(), False
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            in_code = not in_code
        match = re.match(r"^#+ (.*)", line)
        if match and not in_code:
            found.add(slug(match.group(1)))
    return found


def broken_links(root):
    pages = glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True)
    pages += glob.glob(os.path.join(root, "*.md"))
    anchors = {os.path.normpath(p): headings(p) for p in pages}
    for page in pages:
        text = open(page, encoding="utf-8").read()
        for link in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"^[a-z]+:", link):
                continue  # http:, https:, mailto:
            target, _, anchor = link.partition("#")
            path = os.path.normpath(os.path.join(os.path.dirname(page), target)) if target else os.path.normpath(page)
            if not os.path.exists(path):
                yield f"{os.path.relpath(page, root)}: {link}: no such file"
            elif anchor and path.endswith(".md") and anchor not in anchors.get(path, set()):
                yield f"{os.path.relpath(page, root)}: {link}: no heading #{anchor} there"


if __name__ == "__main__":
    bad = list(broken_links(sys.argv[1] if len(sys.argv) > 1 else "."))
    for line in bad:
        print(line)
    sys.exit(1 if bad else 0)
