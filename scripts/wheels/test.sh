#!/usr/bin/env bash
# `make test-wheel`: installs a built wheel (default: dist/'s cp312 one, of `make wheel`)
# into a bare venv of CPython 3.12 (pyenv's; no system site packages) with CC=false and
# CXX=false, so that anything compiling at install time fails, then runs
# python/wheel_tests/test_wheel.py from a temporary folder outside the repository.
#
#   scripts/wheels/test.sh [WHEEL]
#
# WHEEL_TEST_SB3=1 also installs stable-baselines3 (PyPI's torch: about 3 GB with its CUDA
# libraries, several minutes to download) for the SB3 training and converter tests, which
# are skipped without it. WHEEL_TEST_PYTHON picks another version (default 3.12).
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
version="${WHEEL_TEST_PYTHON:-3.12}"
tag="cp${version/./}"
wheel="${1:-}"
if [ -z "$wheel" ]; then
  wheel=$(ls "$repo_dir"/dist/upkie_rl-*-"$tag"-"$tag"-manylinux*.whl 2>/dev/null | tail -n 1 || true)
  if [ -z "$wheel" ]; then
    echo "test-wheel: no $tag wheel in $repo_dir/dist: run 'make wheel' first" >&2
    exit 1
  fi
fi
if [ ! -f "$wheel" ]; then
  echo "test-wheel: $wheel is not a file" >&2
  exit 1
fi
wheel="$(cd "$(dirname "$wheel")" && pwd)/$(basename "$wheel")"
python="$(bash "$repo_dir/scripts/wheels/python-for.sh" "$version")"
venv="${WHEEL_TEST_VENV:-$repo_dir/.venv-wheel-test}"
work_dir="$(mktemp -d /tmp/upkie-rl-wheel-test.XXXXXX)"
trap 'rm -rf "$work_dir"' EXIT

rm -rf "$venv"
"$python" -m venv "$venv"
pip=("$venv/bin/python" -m pip --disable-pip-version-check)
# Nothing may compile: a dependency without a wheel for this Python fails here.
export CC=false CXX=false
elapsed() { awk -v start="$1" -v end="$EPOCHREALTIME" 'BEGIN { printf "%.1f", end - start }'; }
start=$EPOCHREALTIME
"${pip[@]}" install --quiet --only-binary :all: "$wheel"
echo "test-wheel: pip install $(basename "$wheel") took $(elapsed "$start") s"
"${pip[@]}" install --quiet --only-binary :all: pytest
if [ "${WHEEL_TEST_SB3:-0}" = "1" ]; then
  start=$EPOCHREALTIME
  "${pip[@]}" install --quiet --only-binary :all: "stable-baselines3>=2.4" pyyaml
  echo "test-wheel: pip install stable-baselines3 took $(elapsed "$start") s"
fi

cp "$repo_dir/python/wheel_tests/test_wheel.py" "$work_dir/"
cp -r "$repo_dir/tests/data/policies" "$work_dir/policies"
cd "$work_dir"
# Nothing of a source tree or a build tree may be found.
env -u PYTHONPATH -u UPKIE_RL_MODEL -u UPKIE_RL_BUILD_DIR \
  UPKIE_RL_WHEEL_TEST_POLICIES="$work_dir/policies" \
  "$venv/bin/python" -m pytest -q -p no:cacheprovider test_wheel.py
