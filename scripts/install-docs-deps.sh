#!/usr/bin/env bash
# Installs the docs site's packages (docs/requirements.txt: MkDocs, Material, mkdocstrings)
# from PyPI into a virtual environment of their own, .venv-docs (or DOCS_VENV), once: a
# venv whose packages already match the requirements is left as it is. The venv is made by
# Debian's interpreter (/usr/bin/python3, or PYTHON).
set -euo pipefail
cd "$(dirname "$0")/.."
python=${PYTHON:-/usr/bin/python3}
venv=${DOCS_VENV:-.venv-docs}
requirements=docs/requirements.txt
stamp="$venv/.requirements-installed"
if [ -x "$venv/bin/mkdocs" ] && [ -f "$stamp" ] && cmp -s "$requirements" "$stamp"; then
  exit 0
fi
if [ ! -x "$venv/bin/python" ]; then
  "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$requirements"
cp "$requirements" "$stamp"
echo "docs packages installed in $venv"
