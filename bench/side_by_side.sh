#!/usr/bin/env bash
# A budget on a machine whose speed is not its recorded one (docs/performance.md, "Budgets on a slow day"): the
# benchmark of a baseline commit and of this checkout's HEAD, each from a fresh clone, built cold
# (CCACHE_DISABLE=1), one after the other with nothing else running. Prints each one's build time, study time and
# folder size as scripts/benchmark.sh reports them, and the ratios: the change's cost at the recorded speed is the
# baseline's recorded figure (docs/budgets.md) times the ratio. With --ci, each side runs CI (.ci/run, the test
# command) instead, and the ratios are of its phases as scripts/test.sh prints them.
#   bench/side_by_side.sh BASELINE_COMMIT SCRATCH_FOLDER [--ci | benchmark.sh options, e.g. --full]
set -euo pipefail
cd "$(dirname "$0")/.."
if (($# < 2)); then
  echo "usage: bench/side_by_side.sh BASELINE_COMMIT SCRATCH_FOLDER [benchmark.sh options]" >&2
  exit 2
fi
baseline=$1 scratch=$2
shift 2
if ! git rev-parse --verify --quiet "$baseline^{commit}" >/dev/null; then
  echo "side_by_side.sh: '$baseline' is no commit of this repository" >&2
  exit 2
fi
if [[ -e $scratch ]]; then
  echo "side_by_side.sh: $scratch exists; give a folder that does not (the clones and results go there)" >&2
  exit 2
fi
repository=$(pwd)
head=$(git rev-parse --short HEAD)
mkdir -p "$scratch"
export CCACHE_DISABLE=1
seconds_of() {  # M:SS -> seconds
  local m=${1%%:*} s=${1##*:}
  echo $((10#$m * 60 + 10#$s))
}
# A fresh clone of SIDE's commit (baseline or head) in SCRATCH/SIDE, said with the time and load it starts at;
# WHAT: what runs there, as the line names it.
clone_side() {
  local side=$1 what=$2 commit=$baseline
  [[ $side == head ]] && commit=$head
  git clone -q "$repository" "$scratch/$side"
  git -C "$scratch/$side" checkout -q "$commit"
  echo "side_by_side: $what$side ($commit) from $(date +%T), load average $(cut -d' ' -f1-3 /proc/loadavg)"
}
if [[ ${1:-} == --ci ]]; then
  # the phases scripts/test.sh prints at its end, "  NAME   M:SS", the same names on both sides
  phases_of() { sed -n '/^test: phases/,$ s/^  \(.*[^ ]\) \{2,\}\([0-9]*:[0-9][0-9]\)$/\1|\2/p' "$1"; }
  for side in baseline head; do
    clone_side "$side" "CI of "
    (cd "$scratch/$side" && .ci/run) >"$scratch/$side.log" 2>&1 || echo "side_by_side: $side's CI failed (log: $scratch/$side.log)"
  done
  # a phase's name carries its test count, "tests (175 in build/)": compared by its words before the count
  join -t'|' <(phases_of "$scratch/baseline.log" | sed 's/ ([0-9]* in /(in /' | sort) \
             <(phases_of "$scratch/head.log" | sed 's/ ([0-9]* in /(in /' | sort) |
    while IFS='|' read -r phase before after; do
      awk -v b="$(seconds_of "$before")" -v h="$(seconds_of "$after")" -v w="$phase" -v x="$before" -v y="$after" \
        'BEGIN { printf "side_by_side: %-36s baseline %6s  HEAD %6s  HEAD / baseline = %.2f\n", w, x, y, h / b }'
    done
  exit 0
fi
declare -A build study size
for side in baseline head; do
  clone_side "$side" ""
  (cd "$scratch/$side" && scripts/benchmark.sh "$@" "$scratch/$side-results") >"$scratch/$side.log" 2>&1 || true
  build[$side]=$(sed -n 's/^benchmark: installed and built in \([0-9:]*\).*/\1/p' "$scratch/$side.log")
  study[$side]=$(sed -n 's/^benchmark: .*study done in \([0-9:]*\).*/\1/p' "$scratch/$side.log")
  size[$side]=$(sed -n 's/^benchmark: .*study done in [0-9:]* (build excluded), \([^ ]*\) of results.*/\1/p' "$scratch/$side.log")
  echo "side_by_side: $side built in ${build[$side]:-?}, study in ${study[$side]:-?}, ${size[$side]:-?} (log: $scratch/$side.log)"
done
ratio() {  # what, the baseline's M:SS, HEAD's M:SS
  [[ -n $2 && -n $3 ]] || return 0
  awk -v b="$(seconds_of "$2")" -v h="$(seconds_of "$3")" -v w="$1" \
    'BEGIN { printf "side_by_side: %s, HEAD / baseline = %.2f\n", w, h / b }'
}
ratio build "${build[baseline]}" "${build[head]}"
ratio study "${study[baseline]}" "${study[head]}"
