#!/usr/bin/env bash
# Installs the Debian 12 packages impactbench needs, only those missing. Idempotent; run as root (or with
# sudo available). Every package and which command needs it: README.md, "Dependencies".
#
#   scripts/install-deps.sh            what the benchmark needs (scripts/benchmark.sh): build tools, the
#                                      libraries, the engines, the report's Python packages
#   scripts/install-deps.sh --bench    and Google Benchmark and SUNDIALS, for bench/ (benchmark.sh --full)
#   scripts/install-deps.sh --tests    and what only the tests need (scripts/test.sh)
#   IMPACTBENCH_EXTRA_PACKAGES="..." scripts/install-deps.sh --only-extra
#                                      just those (scripts/fuzz.sh: clang; overhead_instructions.sh: valgrind)
set -euo pipefail

benchmark_packages=(
  cmake g++ ninja-build pkg-config  # build (Ninja: the fastest generator CMake has here)
  libeigen3-dev                  # generalised eigenproblem of the link chain
  libboost-dev                   # odeint (Dormand-Prince), math (TOMS 748 roots, Gauss-Legendre)
  libtomlplusplus-dev            # scenario files
  nlohmann-json3-dev             # summary.json, runs.jsonl
  libcli11-dev                   # command line
  zlib1g-dev                     # gzip: series.csv.gz read back
  libdeflate-dev                 # gzip: the .gz tables written, whole-buffer (faster than zlib)
  libssl-dev                     # libcrypto's SHA-256: each engine's library file hashed into provenance.json
  libmujoco-dev libqhull-dev      # MuJoCo 2.2.2 (its CMake config names qhull's headers)
  libode-dev                     # ODE 0.16.2, double precision
  libbullet-dev                  # Bullet 3.24, linked as bullet-float64 (double precision)
  libdart-dev                    # DART 6.12.1, its core component only (collision-bullet links float Bullet)
  libsimbody-dev                 # Simbody 3.7 (Hunt-Crossley contact, rigid-contact stepper, CPodes)
  siconos                        # Siconos 4.4: Moreau-Jean time stepping, Newton's impact law (its CMake config
                                 # needs the siconos script and all six libraries: the whole package, about 50 more)
  python3-matplotlib             # the report's figures (reports/, run with /usr/bin/python3)
  python3-scipy                  # the report's spectra and scalograms; bench/'s reference against solve_ivp
)
bench_packages=(
  libbenchmark-dev               # bench/: speed measurements (benchmark.sh --full, the tests build them too)
  libsundials-dev                # bench/cvode_reference: CVODE beside SciPy on the reference's equations (its test too)
)
test_packages=(
  libgtest-dev libgmock-dev      # the tests (GoogleTest through ctest)
  slurmctld slurmd slurm-client munge  # tests/slurm/: a real one-node Slurm cluster runs the job-array scripts
  chromium                       # report_in_chromium: the report's page rendered as a reader sees it
  clang-format                   # ctest format (scripts/check_format.sh): the sources as .clang-format has them
)

packages=("${benchmark_packages[@]}")
case "${1:-}" in
  "") ;;
  --bench) packages+=("${bench_packages[@]}") ;;
  --tests) packages+=("${bench_packages[@]}" "${test_packages[@]}") ;;
  --only-extra) read -r -a packages <<<"${IMPACTBENCH_EXTRA_PACKAGES:-}" ;;
  *) echo "install-deps: unknown option '$1'; allowed: none, --bench, --tests, --only-extra" >&2; exit 2 ;;
esac

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo; install as root: apt-get install ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
# Slurm's and munge's packages start their daemons when installed on a machine with an init system; the
# tests start their own cluster on loopback (scripts/slurm/cluster.sh), so no service is started while
# installing: a policy-rc.d that refuses every start, only for this install and only if there is none.
policy=/usr/sbin/policy-rc.d
if [[ ! -e $policy ]]; then
  "${sudo[@]}" sh -c "printf '#!/bin/sh\n# impactbench install-deps: no service starts during this install\nexit 101\n' > $policy && chmod 755 $policy"
  trap '"${sudo[@]}" rm -f "$policy"' EXIT
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
