#!/usr/bin/env bash
# Installs what upkie-rl needs to build and test: Debian packages, then the Python test
# packages. Idempotent: installs only what is missing. Works as root or through sudo.
set -euo pipefail

# Debian 12 (bookworm) and Debian 13 (trixie), which name a few packages differently: the
# per-release ones are set here and used in the lists below.
# shellcheck source=/dev/null
. /etc/os-release
case "${VERSION_CODENAME:-}" in
  bookworm)
    LLVM_VERSION=14
    # Debian 12's torch (1.13) is built against NumPy 1.x.
    NUMPY_REQUIREMENT="numpy<2"
    YAML_CPP_LIBRARY=libyaml-cpp0.7 URDFDOM_MODEL_LIBRARY=liburdfdom-model3.0
    ;;
  trixie)
    LLVM_VERSION=19
    # Debian 13's torch (2.6) is built against its NumPy 2.2 (python3-numpy).
    NUMPY_REQUIREMENT="numpy>=2"
    YAML_CPP_LIBRARY=libyaml-cpp0.8 URDFDOM_MODEL_LIBRARY=liburdfdom-model4.0
    ;;
  *)
    echo "install-deps: Debian 12 (bookworm) or 13 (trixie) expected, not" \
      "'${PRETTY_NAME:-unknown}'" >&2
    exit 1
    ;;
esac

DEBIAN_PACKAGES=(
  build-essential cmake ninja-build pkg-config git ccache
  libbullet-dev liburdfdom-dev libtinyxml-dev libeigen3-dev libtorch-dev python3-torch
  libgloo-dev  # c10d's Gloo process group, for distributed training
  libopenblas0-serial  # single-threaded OpenBLAS for libtorch: the reference BLAS is slow
  libmsgpack-cxx-dev libboost-dev nlohmann-json3-dev libcli11-dev libyaml-cpp-dev
  libspdlog-dev libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox fonts-liberation
  clang-format clang-tidy python3-pip python3-pytest python3-numpy
  python3-dev  # the upkie_rl Python extension module (pybind11 from the registry, below)
  libnlopt-dev  # `upkie-rl identify` fits a robot's log with NLopt's BOBYQA
  libonnx-dev  # ONNX export: the ONNX project's protobuf classes and checker
  python3-yaml  # upkie_rl.sb3_convert reads and writes training configurations
  python3-venv  # the venvs of the newest-Gymnasium tests and of the docs site (make docs)
  # offscreen rendering without display or GPU (EGL, Mesa's llvmpipe), videos (H.264, GIF)
  libegl-dev libegl-mesa0 libgl1-mesa-dri ffmpeg
  # the browser viewer's tests: Debian's Chromium, driven by playwright-core (npm)
  chromium
  # the robot runner for the robot's Raspberry Pi (aarch64): cross compiler, and qemu-user
  # to test it here (`make pi`, tests/agent)
  g++-aarch64-linux-gnu qemu-user
  # libFuzzer's runtime (built against libstdc++): `make test` links the fuzz targets built
  # by GCC with it for bounded mutation fuzzing (FuzzBounded.*, fuzz/CMakeLists.txt)
  "libclang-rt-$LLVM_VERSION-dev"
)
# The compiled libraries the aarch64 runner links, Debian's arm64 builds (multiarch): their
# headers are the native -dev packages above.
ARM64_PACKAGES=("$YAML_CPP_LIBRARY:arm64" "$URDFDOM_MODEL_LIBRARY:arm64" libtinyxml2.6.2v5:arm64
  libconsole-bridge1.0:arm64)
# Node.js and npm bundle the viewer page (web/viewer). Debian's packages only when the
# machine has no node: a NodeSource or nvm node brings its own npm, which Debian's would
# conflict with.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  DEBIAN_PACKAGES+=(nodejs npm)
fi
# Python packages as "module:requirement". They go to Debian's interpreter, whose
# python3-torch SB3 needs (PyPI's torch is a multi-GB CUDA build). SB3 2.4.x is the last
# release that accepts torch 1.13 (Debian 12's); it pins gymnasium < 1.1. NumPy: the major
# version Debian's torch is built against (NUMPY_REQUIREMENT, above). upkie: the public agent side, for the spine interoperability
# tests. mujoco: its wheel ships libmujoco.so 3.3 and the C headers, which CMake links
# (Debian has only MuJoCo 2.2, without the mjSpec API the model is built with). moviepy:
# Gymnasium's RecordVideo writes with it. onnxruntime: the tests run exported ONNX policies
# with it (its wheels accept numpy 1.x).
# gymnasium: the oldest release the package supports (pyproject.toml), which SB3 2.4.1 also
# accepts; the newest is tested in a venv of its own (below). mypy: `make test-python`
# type-checks the package and its stubs. hypothesis: the fuzzing of the package's readers
# and public functions (python/tests/fuzz_inputs.py, `make fuzz-python`).
PYTHON_PACKAGES=(
  "pytest:pytest" "numpy:$NUMPY_REQUIREMENT" "gymnasium:gymnasium==1.0.0" "msgpack:msgpack"
  "upkie:upkie" "tensorboard:tensorboard" "scikit_build_core:scikit-build-core"
  "pybind11:pybind11" "cloudpickle:cloudpickle" "pandas:pandas" "matplotlib:matplotlib"
  "mujoco:mujoco>=3.3,<3.4" "moviepy:moviepy" "mpacklog:mpacklog" "onnxruntime:onnxruntime" "mypy:mypy"
  "hypothesis:hypothesis"
)
# Installed without their dependencies, which are listed above: Debian's torch calls
# itself 1.13.0a0, a pre-release that SB3's "torch>=1.13" refuses, so pip would fetch
# PyPI's torch instead.
PYTHON_PACKAGES_NO_DEPS=("stable_baselines3:stable-baselines3==2.4.1")
# Long fuzzing (`make fuzz` sets UPKIE_RL_FUZZ=1): clang, for libFuzzer's own coverage
# instrumentation of every library (its runtime is in the list above).
if [ "${UPKIE_RL_FUZZ:-0}" = "1" ]; then
  DEBIAN_PACKAGES+=("clang-$LLVM_VERSION")
fi

if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi

# The packages among the arguments that are not installed, one per line.
missing_packages() {
  for package in "$@"; do
    if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
      echo "$package"
    fi
  done
}
mapfile -t missing < <(missing_packages "${DEBIAN_PACKAGES[@]}")
if [ "${#missing[@]}" -gt 0 ]; then
  echo "install-deps: installing Debian packages: ${missing[*]}"
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
else
  echo "install-deps: Debian packages present"
fi
mapfile -t missing_arm64 < <(missing_packages "${ARM64_PACKAGES[@]}")
if [ "${#missing_arm64[@]}" -gt 0 ]; then
  echo "install-deps: installing arm64 libraries: ${missing_arm64[*]}"
  if ! dpkg --print-foreign-architectures | grep -qx arm64; then
    $SUDO dpkg --add-architecture arm64
  fi
  $SUDO apt-get update -q
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing_arm64[@]}"
fi

# Python packages go to the interpreter that builds the extension and runs pytest:
# Debian's /usr/bin/python3 (the one with python3-torch), unless PYTHON says otherwise.
PYTHON="${PYTHON:-/usr/bin/python3}"
missing_python=()
for entry in "${PYTHON_PACKAGES[@]}"; do
  module="${entry%%:*}"
  if ! "$PYTHON" -c "import ${module}" 2>/dev/null; then missing_python+=("${entry#*:}"); fi
done
missing_no_deps=()
for entry in "${PYTHON_PACKAGES_NO_DEPS[@]}"; do
  module="${entry%%:*}"
  if ! "$PYTHON" -c "import ${module}" 2>/dev/null; then missing_no_deps+=("${entry#*:}"); fi
done
pip_flags=(--quiet --disable-pip-version-check)
if "$PYTHON" -m pip install --help 2>/dev/null | grep -q -- --break-system-packages; then
  # Debian's own interpreter is externally managed; a pyenv one is not, and ignores this.
  pip_flags+=(--break-system-packages)
fi
if [ "${#missing_python[@]}" -gt 0 ]; then
  echo "install-deps: installing Python packages: ${missing_python[*]}"
  # NUMPY_REQUIREMENT always: pip must not change the NumPy major version Debian's torch
  # was built against.
  "$PYTHON" -m pip install "${pip_flags[@]}" "$NUMPY_REQUIREMENT" "${missing_python[@]}"
else
  echo "install-deps: Python packages present"
fi
if [ "${#missing_no_deps[@]}" -gt 0 ]; then
  echo "install-deps: installing Python packages without dependencies: ${missing_no_deps[*]}"
  "$PYTHON" -m pip install "${pip_flags[@]}" --no-deps "${missing_no_deps[@]}"
fi

# The newest Gymnasium that pyproject.toml allows, with the newest NumPy 2, in a venv of its
# own that sees Debian's interpreter's packages (torch, pytest, mujoco, moviepy): `make
# test-python` runs the Python tests against it too, so that the package is tested under
# NumPy 1.26 (Debian's interpreter) and NumPy 2 (here). Installed once: remove the venv to
# take newer releases.
repo_dir="$(cd "$(dirname "$0")/.." && pwd)"
newest_venv="${GYMNASIUM_NEWEST_VENV:-$repo_dir/.venv-gymnasium-newest}"
gymnasium_requirement="$("$PYTHON" -c "import sys, tomllib
project = tomllib.load(open(sys.argv[1], 'rb'))['project']
print(next(d for d in project['dependencies'] if d.startswith('gymnasium')))" "$repo_dir/pyproject.toml")"
if [ ! -x "$newest_venv/bin/python" ]; then
  echo "install-deps: creating $newest_venv (newest $gymnasium_requirement, numpy>=2)"
  "$PYTHON" -m venv --system-site-packages "$newest_venv"
fi
# Gymnasium and NumPy must be the venv's own, not Debian's interpreter's (Gymnasium 1.0.0,
# NumPy 1.26) seen through it; NumPy a 2.x.
if ! "$newest_venv/bin/python" - <<'PYTHON_CHECK' 2>/dev/null; then
import sys, importlib.metadata as metadata
def own(name):
    return metadata.distribution(name).locate_file("").as_posix().startswith(sys.prefix)
numpy_major = int(metadata.version("numpy").split(".")[0])
sys.exit(0 if own("gymnasium") and own("numpy") and numpy_major >= 2 else 1)
PYTHON_CHECK
  echo "install-deps: installing $gymnasium_requirement and numpy>=2 (newest) in $newest_venv"
  "$newest_venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --upgrade --upgrade-strategy only-if-needed "$gymnasium_requirement" "numpy>=2"
else
  echo "install-deps: newest Gymnasium venv present ($newest_venv)"
fi

# The viewer's npm packages, exactly as package-lock.json says, again whenever it changes
# (web/viewer/build.mjs refuses to bundle with stale packages).
viewer_dir="$repo_dir/web/viewer"
if [ ! -f "$viewer_dir/node_modules/.package-lock.json" ] ||
   [ "$viewer_dir/package-lock.json" -nt "$viewer_dir/node_modules/.package-lock.json" ]; then
  echo "install-deps: installing the viewer's npm packages (npm ci)"
  (cd "$viewer_dir" && npm ci --no-audit --no-fund --loglevel=error)
else
  echo "install-deps: viewer npm packages present"
fi
