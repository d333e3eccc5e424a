#!/usr/bin/env bash
# Prints the path of a CPython interpreter of the version given (3.10, 3.11, 3.12 or 3.13),
# the ones `make wheel` builds for: pyenv's ($PYENV_ROOT/versions/<version>.*, the newest
# patch release there), else python<version> on PATH (Debian 13's python3.13, deadsnakes' on
# Ubuntu). The interpreter needs its C headers (pyenv's have them; Debian's need
# python3.X-dev) and its venv module.
#
# Another machine gets the four with pyenv (https://github.com/pyenv/pyenv#installation), which
# compiles each from python.org's sources (Debian needs build-essential libssl-dev zlib1g-dev
# libbz2-dev libreadline-dev libsqlite3-dev libffi-dev liblzma-dev tk-dev uuid-dev first):
#   pyenv install 3.10 3.11 3.12 3.13
# The wheels of this repository were built with pyenv's 3.10.13, 3.11.7, 3.12.1 and 3.13.0.
set -euo pipefail

version="${1:-}"
if [[ ! "$version" =~ ^3\.[0-9]+$ ]]; then
  echo "usage: $0 3.X (a CPython version such as 3.12, got '${version}')" >&2
  exit 2
fi
pyenv_root="${PYENV_ROOT:-$HOME/.pyenv}"
# The newest patch release of that version under pyenv (3.12.10 after 3.12.9).
candidate=$(ls -d "$pyenv_root/versions/$version".* 2>/dev/null | grep -E "/$version\.[0-9]+$" |
  sort -V | tail -n 1 || true)
if [ -n "$candidate" ] && [ -x "$candidate/bin/python$version" ]; then
  echo "$candidate/bin/python$version"
  exit 0
fi
if command -v "python$version" >/dev/null 2>&1; then
  command -v "python$version"
  exit 0
fi
echo "no CPython $version: neither $pyenv_root/versions/$version.* nor python$version on PATH;" \
  "install it with 'pyenv install $version' (see the comment at the top of $0)" >&2
exit 1
