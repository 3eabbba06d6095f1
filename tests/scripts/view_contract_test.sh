#!/usr/bin/env bash
# The architecture issue 45 set up, kept: libraries never name a command-line flag (they name
# settings; cli/flags maps them), the view folder's names are spelled in the view module only,
# model/ and eval/ never parse view.json or manifest.json themselves, and no source folder
# holds more than 40 files. Each check prints what breaks it.
#   $1 = phyir binary (unused), $2 = scratch folder (unused).
set -euo pipefail
root=${PHYIR_SOURCE_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
cd "$root"
fail=0
check() {  # description, command printing offending lines
  local out
  out=$(eval "$2" || true)
  if [ -n "$out" ]; then echo "FAIL: $1:"; echo "$out"; fail=1; fi
}
check "a library names a command-line flag" \
  "git grep -nE -- '--[a-z][a-z0-9-]+' -- core scenes render dataset eval model view insert ':!*.md'"
check "a view-folder name spelled outside the view module" \
  "git grep -lE '\"(probes|probe_mask|probe_stderr)\\.exr\"|\"exposure_stops\"' -- ':!tests' ':!docs' ':!view'"
check "model/ or eval/ parses a record itself" \
  "git grep -nE '\"(view|manifest)\\.json\"|json::parse\\(read_file' -- model eval"
check "a source folder of over 40 files" \
  "for d in \$(git ls-files -- '*.cpp' '*.h' | xargs -n1 dirname | sort -u); do n=\$(git ls-files -- \"\$d\" | grep -c \"^\$d/[^/]*\$\"); [ \"\$n\" -gt 40 ] && echo \"\$d: \$n files\"; done"
[ $fail = 0 ] && echo "view contract: OK"
exit $fail
