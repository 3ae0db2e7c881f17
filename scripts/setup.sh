#!/usr/bin/env bash
# Installs the Debian packages sinew needs (apt-get only, skipped when already there) and builds it.
# usage: scripts/setup.sh [--sanitize]   (the sanitizer build goes to build-sanitize/)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake pkg-config libsimbody-dev libeigen3-dev libyaml-cpp-dev libgtest-dev libbenchmark-dev
          libpugixml-dev libtinyxml2-dev coinor-libclp-dev libsuitesparse-dev coinor-libipopt-dev libmujoco-dev python3 python3-matplotlib
          libcairo2-dev nlohmann-json3-dev libjs-three chromium chromium-driver
          python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest  # the Python module (docs/python.md)
          python3-yaml python3-distributed  # sinew_batch's manifests and Dask scale-out (docs/batch.md)
          clang libclang-rt-dev libomp-dev)  # clang, its runtimes and OpenMP for the fuzzers (fuzz/run.sh)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}"
fi

build_dir=build
cmake_args=()
if [ "${1:-}" = "--sanitize" ]; then
  build_dir=build-sanitize
  cmake_args+=(-DSINEW_SANITIZE=ON -DSINEW_BUILD_BENCHMARKS=OFF -DSINEW_OPT_FLAGS=-O1)
fi
cmake -S . -B "$build_dir" "${cmake_args[@]}" >/dev/null
cmake --build "$build_dir" -j "$(nproc)"
echo "setup: built $build_dir/bin/sinew"
