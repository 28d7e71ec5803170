#!/usr/bin/env bash
# Checks that every C++ file of the repository is formatted as .clang-format says
# (clang-format 14, Debian's). Lists the files that are not and exits 1; fix with
#   clang-format -i $(git ls-files '*.cpp' '*.hpp' '*.h')
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh clang-format
bad=()
while IFS= read -r file; do
  clang-format --dry-run -Werror "$file" >/dev/null 2>&1 || bad+=("$file")
done < <(git ls-files '*.cpp' '*.hpp' '*.h')
if [ ${#bad[@]} -gt 0 ]; then
  echo "not formatted as .clang-format says (clang-format -i FILE fixes it):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "format check: $(git ls-files '*.cpp' '*.hpp' '*.h' | wc -l) files formatted"
