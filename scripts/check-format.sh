#!/usr/bin/env bash
# Fails, listing the files, when a C or C++ source differs from .clang-format's layout.
# Fix with: clang-format -i FILE...  (tables and formulas whose layout carries meaning sit
# between "// clang-format off" and "// clang-format on").
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(find src include tests bench examples fuzz -name '*.cpp' -o -name '*.hpp' -o -name '*.h' -o -name '*.c' | sort)
unformatted=()
for file in "${files[@]}"; do
  clang-format --dry-run -Werror "$file" 2>/dev/null || unformatted+=("$file")
done
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "not in the .clang-format layout (run clang-format -i on them):" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  exit 1
fi
echo "${#files[@]} sources in the .clang-format layout"
