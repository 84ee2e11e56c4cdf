#!/usr/bin/env bash
# The harness's overhead counted in instructions instead of time: harness_overhead_benchmark's two sides
# (the engine's run through the Simulator interface, and the bare loop) under valgrind's callgrind, which
# counts the instructions each executes. Instructions are not time (cache misses, branch mispredictions),
# but the count is the same on every run, whereas on a shared machine (a cloud VM) the timed benchmark
# moves by several percent between runs. Each side runs twice (the benchmark's untimed pair and one timed
# pair), the same for both. About 6 minutes on 2 cores. Installs Debian's valgrind when it is missing.
#   bench/overhead_instructions.sh [OUT]     (default OUT: results/performance)
# Writes OUT/harness_overhead_instructions.csv: engine, law, harness and bare instructions, overhead [%].
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v valgrind >/dev/null; then
  sudo=(); [[ $(id -u) -ne 0 ]] && sudo=(sudo)
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends valgrind
fi
out=${1:-results/performance}
mkdir -p "$out"
benchmark=build/bench/harness_overhead_benchmark
[[ -x $benchmark ]] || { echo "overhead_instructions.sh: $benchmark missing: build it first (scripts/build.sh --bench)" >&2; exit 2; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
cases=$("$benchmark" --benchmark_list_tests)  # engine/law, as this build has them
# shellcheck disable=SC2016
xargs -P 2 -I{} sh -c 'valgrind --tool=callgrind --callgrind-out-file="$1/$(echo "$2" | tr / _).out" \
    "$3" --benchmark_filter="^$2\$" --benchmark_min_time=0 >/dev/null 2>&1' _ "$scratch" {} "$benchmark" <<<"$cases"
csv="$out/harness_overhead_instructions.csv"
echo "engine,law,harness_instructions,bare_instructions,overhead_percent" >"$csv"
for name in $cases; do
  # inclusive counts of the two sides' functions: <Engine>Simulator::run and bare_<engine>
  read -r harness bare < <(callgrind_annotate --inclusive=yes "$scratch/${name/\//_}.out" |
    awk '/Simulator::run\(/ && !/lambda/ && !h { gsub(",", "", $1); h = $1 }
         /bare_[a-z]+\(/ && !b { gsub(",", "", $1); b = $1 }
         END { print h, b }')
  [[ -n $harness && -n $bare ]] || { echo "overhead_instructions.sh: no counts for $name" >&2; exit 1; }
  awk -v name="$name" -v h="$harness" -v b="$bare" \
    'BEGIN { split(name, p, "/"); printf "%s,%s,%s,%s,%.2f\n", p[1], p[2], h, b, 100 * (h / b - 1) }' >>"$csv"
done
column -s, -t "$csv"
echo "overhead_instructions.sh: $csv"
