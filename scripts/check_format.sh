#!/usr/bin/env bash
# The formatter's check (ctest "format"): every tracked C/C++ file is as clang-format leaves it with the
# repository's .clang-format (Google style, 120 columns, each include block sorted). Lists the files that
# differ and how to fix them. Exit 0: all formatted; 1: some differ; 2: clang-format (Debian's clang-format
# package, installed by scripts/install-deps.sh --tests) or git missing.
#   scripts/check_format.sh      CLANG_FORMAT=/path/to/clang-format to use another binary
set -euo pipefail
cd "$(dirname "$0")/.."

clang_format=${CLANG_FORMAT:-clang-format}
if ! command -v "$clang_format" >/dev/null; then
  echo "check_format: $clang_format not found; install Debian's clang-format (apt-get install clang-format," \
       "or scripts/install-deps.sh --tests)" >&2
  exit 2
fi
if ! git rev-parse --git-dir >/dev/null 2>&1; then
  echo "check_format: $(pwd) is not a git checkout; the check reads the tracked files (git ls-files)" >&2
  exit 2
fi

# The tracked C/C++ sources; tests/data/ holds corpora (malformed scenarios, fuzz seeds), never formatted.
mapfile -t files < <(git ls-files -- '*.h' '*.cpp' '*.cc' '*.hpp' ':!:tests/data/*')
status=0
output=$("$clang_format" --dry-run --Werror "${files[@]}" 2>&1) || status=$?
if ((status == 0)); then
  echo "check_format: ${#files[@]} files formatted ($("$clang_format" --version))"
  exit 0
fi
mapfile -t differ < <(sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' <<<"$output" | uniq)
if ((${#differ[@]} == 0)); then  # clang-format failed otherwise (e.g. a bad .clang-format): its own words
  echo "$output" >&2
  echo "check_format: $clang_format failed (exit code $status)" >&2
  exit 1
fi
echo "check_format: ${#differ[@]} of ${#files[@]} files are not formatted ($("$clang_format" --version)):"
printf '  %s\n' "${differ[@]}"
echo "Fix each with: clang-format -i FILE (e.g. clang-format -i ${differ[0]}); see what differs with:" \
     "clang-format FILE | diff FILE -"
exit 1
