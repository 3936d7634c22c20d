# Shared by tools/demo and tools/check: finding the repo, installing what is missing.
# shellcheck shell=bash

NTN_ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export NTN_ROOT

# Debian packages the build and the tests need (all by name, nothing downloaded at build time).
NTN_PACKAGES=(cmake ninja-build g++ make pkg-config libeigen3-dev libfftw3-dev libtomlplusplus-dev
              libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev libxxhash-dev clang-format
              libspectra-dev gnuplot-nox libexpat1-dev libhwy-dev pybind11-dev python3-dev
              python3-numpy python3-pytest python3-matplotlib libopenmpi-dev openmpi-bin
              libboost-dev)

ntn_jobs() { nproc 2>/dev/null || echo 2; }

# Installs missing packages (NTN_PACKAGES and any named as arguments: a benchmark's own) when
# root; otherwise prints the exact command and stops.
ntn_install_missing() {
  local missing=()
  for p in "${NTN_PACKAGES[@]}" "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  if [ "$(id -u)" -ne 0 ]; then
    echo "Missing Debian packages. Install them with:" >&2
    echo "  sudo apt-get update && sudo apt-get install -y ${missing[*]}" >&2
    exit 1
  fi
  echo "== installing: ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# ntn_configure PRESET [CACHE ARGS...]: configure one preset (CMakePresets.json: Ninja). A build
# folder made by an earlier version with Makefiles is reconfigured from scratch (CMake refuses to
# switch generators in place); its old files stay and are rebuilt over.
ntn_configure() {
  local preset=$1
  shift
  local cache="$NTN_ROOT/.build/$preset/CMakeCache.txt"
  if [ -f "$cache" ] && ! grep -q '^CMAKE_GENERATOR:INTERNAL=Ninja$' "$cache"; then
    echo "== .build/$preset was made with another generator: reconfiguring it for Ninja"
    rm -rf "$cache" "$NTN_ROOT/.build/$preset/CMakeFiles"
  fi
  cmake --preset "$preset" -S "$NTN_ROOT" "$@" >/dev/null
}

# ntn_build PRESET [TARGET...]: configure and build one preset (warnings are errors).
# NTN_CMAKE_ARGS adds cache settings (tools/check leaves the benchmarks out).
ntn_build() {
  local preset=$1
  shift
  # shellcheck disable=SC2086
  ntn_configure "$preset" ${NTN_CMAKE_ARGS:-}
  if [ $# -gt 0 ]; then
    cmake --build --preset "$preset" -j "$(ntn_jobs)" --target "$@"
  else
    cmake --build --preset "$preset" -j "$(ntn_jobs)"
  fi
}
