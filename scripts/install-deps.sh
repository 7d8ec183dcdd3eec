#!/usr/bin/env bash
# Installs Krug's build and test dependencies from Debian 12 packages. Idempotent: packages already
# present are left alone. Run as root (or with sudo available).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libfmt-dev nlohmann-json3-dev catch2 libbenchmark-dev   # library, tests, benchmarks
  libmuparser-dev                                                       # expressions in scenarios
  zlib1g-dev                                                            # compressed binary VTK files
  libcairo2-dev                                                         # PNG pictures (app only)
  libopenmpi-dev openmpi-bin                                            # studies on MPI ranks (app only)
  python3-numpy python3-matplotlib python3-meshio                      # plots, read-back tests
  clang libclang-rt-14-dev                                              # libFuzzer (scripts/fuzz.sh)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
