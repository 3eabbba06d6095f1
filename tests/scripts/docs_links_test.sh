#!/usr/bin/env bash
# Every relative link of the docs reaches a file and a heading (scripts/check_doc_links.py);
# and the check fails on a page with a broken file link and a broken anchor.
#   $1 = phyir binary (unused), $2 = scratch folder.
set -euo pipefail
root=${PHYIR_SOURCE_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
work=${2:-$(mktemp -d)}
rm -rf "$work" && mkdir -p "$work/docs"
python3 "$root/scripts/check_doc_links.py" "$root"
printf '# Page\n\n## A heading\n\n[ok](#a-heading) [bad](#no-heading) [gone](missing.md)\n' > "$work/docs/page.md"
if out=$(python3 "$root/scripts/check_doc_links.py" "$work"); then
  echo "FAIL: broken links were not reported"; exit 1
fi
grep -q "#no-heading" <<<"$out" && grep -q "missing.md: no such file" <<<"$out" && ! grep -q "#a-heading" <<<"$out" \
  || { echo "FAIL: unexpected report: $out"; exit 1; }
echo "docs links: OK"
