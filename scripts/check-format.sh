#!/usr/bin/env bash
# Checks that the tracked C and C++ files (docs/ excepted: its snippets are quoted as
# they were) are formatted as .clang-format says: clang-format names each line that
# differs and the script exits non-zero. The OpenCL C kernels (*.cl) are not checked:
# their macro tables are laid out by hand. To format the checked files:
#   scripts/check-format.sh --fix
# CLANG_FORMAT names the binary (default clang-format; CI: Debian 12's, version 14).
set -euo pipefail
cd "$(dirname "$0")/.."

clang_format=${CLANG_FORMAT:-clang-format}
patterns=('*.c' '*.h' '*.cc' '*.cpp' '*.hpp' ':!:docs/**')
if [[ "${1:-}" == "--fix" ]]; then
  git ls-files -z -- "${patterns[@]}" | xargs -0 -r "$clang_format" -i
  exit 0
fi
git ls-files -z -- "${patterns[@]}" | xargs -0 -r "$clang_format" --dry-run -Werror
echo "check-format: $(git ls-files -- "${patterns[@]}" | wc -l) files as .clang-format lays them out"
