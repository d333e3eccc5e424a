"""The package is typed for users' editors and mypy: py.typed and the extension's stubs are
shipped, and mypy catches a wrong use of the API (it would see Any without them)."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

import upkie_rl


def test_the_package_ships_py_typed_and_stubs():
    package = Path(upkie_rl.__file__).parent
    assert (package / "py.typed").is_file()
    assert (package / "_core.pyi").is_file()


def test_mypy_flags_a_wrong_use_of_predict(tmp_path):
    pytest.importorskip("mypy")
    script = tmp_path / "wrong.py"
    script.write_text(
        "import upkie_rl\n"
        "policy = upkie_rl.load_policy('model.ckpt')\n"
        "actions, state = policy.predict([0.0] * 4, deterministic='yes')\n"
        "name: int = policy.env_id\n")
    # The build tree's package (PYTHONPATH) is where mypy looks for it too.
    environment = dict(os.environ, MYPYPATH=os.environ.get("PYTHONPATH", ""))
    result = subprocess.run(
        [sys.executable, "-m", "mypy", "--no-incremental", "--config-file", os.devnull,
         str(script)], capture_output=True, text=True, env=environment, cwd=tmp_path)
    assert result.returncode == 1, result.stdout
    assert 'Argument "deterministic"' in result.stdout, result.stdout
    assert "str" in result.stdout and 'variable has type "int"' in result.stdout, result.stdout
