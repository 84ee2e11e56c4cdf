#!/usr/bin/env bash
# Installs the Debian 12 packages impactbench needs, only those missing. Idempotent; run as root
# (or with sudo available). Every package and why it is here: README.md, "Dependencies".
set -euo pipefail

packages=(
  cmake g++ make pkg-config      # build
  libeigen3-dev                  # generalised eigenproblem of the link chain
  libboost-dev                   # odeint (Dormand-Prince), math (TOMS 748 roots, Gauss-Legendre)
  libtomlplusplus-dev            # scenario files
  nlohmann-json3-dev             # summary.json
  libcli11-dev                   # command line
  zlib1g-dev                     # gzip: series.csv.gz written and read
  libmujoco-dev libqhull-dev      # MuJoCo 2.2.2 (its CMake config names qhull's headers)
  libode-dev                     # ODE 0.16.2, double precision
  libbullet-dev                  # Bullet 3.24, linked as bullet-float64 (double precision)
  libdart-dev                    # DART 6.12.1, its core component only (collision-bullet links float Bullet)
  libsimbody-dev                 # Simbody 3.7 (Hunt-Crossley contact, rigid-contact stepper, CPodes)
  python3-matplotlib             # the report's figures (reports/, run with /usr/bin/python3)
  python3-scipy                  # bench/reference_vs_scipy.py: the reference against SciPy's solve_ivp
  libgtest-dev libgmock-dev      # tests
  libbenchmark-dev               # bench/: speed measurements
  slurmctld slurmd slurm-client munge  # tests/slurm/: a real one-node Slurm cluster runs the job-array scripts
)

# scripts/fuzz.sh alone needs clang-14 and libclang-rt-14-dev (libFuzzer): it passes them in
# IMPACTBENCH_EXTRA_PACKAGES with --only-extra, so that the normal build never installs them.
if [[ "${1:-}" == --only-extra ]]; then
  read -r -a packages <<<"${IMPACTBENCH_EXTRA_PACKAGES:-}"
fi

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
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
