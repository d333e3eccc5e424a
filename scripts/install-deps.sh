#!/usr/bin/env bash
# Installs what upkie-rl needs to build and test: Debian packages, then the Python test
# packages. Idempotent: installs only what is missing. Works as root or through sudo.
set -euo pipefail

DEBIAN_PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libbullet-dev liburdfdom-dev libtinyxml-dev libeigen3-dev libtorch-dev python3-torch
  libopenblas0-serial  # single-threaded OpenBLAS for libtorch: the reference BLAS is slow
  libmsgpack-cxx-dev libboost-dev nlohmann-json3-dev libcli11-dev libyaml-cpp-dev
  libspdlog-dev libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox fonts-liberation
  clang-format clang-tidy python3-pip python3-pytest python3-numpy
)
# upkie: the public agent side, for the spine interoperability tests.
PYTHON_PACKAGES=(pytest numpy gymnasium msgpack upkie tensorboard)
# Fuzzing (`make fuzz` sets UPKIE_RL_FUZZ=1): clang and its libFuzzer runtime.
if [ "${UPKIE_RL_FUZZ:-0}" = "1" ]; then
  DEBIAN_PACKAGES+=(clang-14 libclang-rt-14-dev)
fi

if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi

missing=()
for package in "${DEBIAN_PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "install-deps: installing Debian packages: ${missing[*]}"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "install-deps: Debian packages present"
fi

# Python test packages go to the interpreter that runs pytest (python3 on PATH).
PYTHON="${PYTHON:-python3}"
missing_python=()
for package in "${PYTHON_PACKAGES[@]}"; do
  if ! "$PYTHON" -c "import ${package}" 2>/dev/null; then missing_python+=("$package"); fi
done
if [ "${#missing_python[@]}" -gt 0 ]; then
  echo "install-deps: installing Python packages: ${missing_python[*]}"
  pip_flags=(--quiet --disable-pip-version-check)
  if "$PYTHON" -m pip install --help 2>/dev/null | grep -q -- --break-system-packages; then
    # Debian's own interpreter is externally managed; a pyenv one is not, and ignores this.
    pip_flags+=(--break-system-packages)
  fi
  "$PYTHON" -m pip install "${pip_flags[@]}" "${missing_python[@]}"
else
  echo "install-deps: Python packages present"
fi
