#!/usr/bin/env bash
# The machine and software a measurement was made with, as key=value lines (no commas in values):
# CPU model, cores, memory, OS, compiler, the engines' and tools' Debian package versions, impactbench's
# commit. bench/run-benchmarks.sh passes them to Google Benchmark as context; bench/suite_scaling.sh
# writes them beside its figures; the report shows them with every measured figure.
set -euo pipefail
cd "$(dirname "$0")/.."
clean() { tr ',\n' '; ' | sed 's/  */ /g; s/ $//'; }
echo "cpu_model=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //' | clean)"
echo "cpu_cores=$(nproc)"
echo "memory_gib=$(awk '/MemTotal/ {printf "%.1f", $2 / 1048576}' /proc/meminfo)"
echo "os=$( (. /etc/os-release && echo "$PRETTY_NAME") | clean)"
echo "compiler=$(c++ --version | head -1 | clean)"
# the engines' packages from their descriptors (adapters/<engine>/descriptor.json), then the tools'
engine_packages=$(/usr/bin/python3 -c 'import glob, json
print(" ".join(dict.fromkeys(p for f in sorted(glob.glob("adapters/*/descriptor.json")) for p in json.load(open(f)).get("packages", []))))')
for p in $engine_packages libbenchmark-dev python3-scipy libsundials-dev; do
  echo "$p=$(dpkg-query -W -f='${Version}' "$p" 2>/dev/null || echo none)"
done
echo "impactbench_commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet HEAD 2>/dev/null || echo '+changes')"
