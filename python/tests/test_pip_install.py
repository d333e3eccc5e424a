"""`pip install .` works: the wheel scikit-build-core builds from this repository installs a
package that runs on its own (robot model inside, no libtorch), away from the build tree.

Builds the C++ environment layers again (about 2 minutes on 2 cores); set
UPKIE_RL_SKIP_PIP_TEST=1 to skip it in quick local runs.
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.skipif(os.environ.get("UPKIE_RL_SKIP_PIP_TEST") == "1",
                    reason="UPKIE_RL_SKIP_PIP_TEST=1")
def test_wheel_installs_and_runs_outside_the_tree(tmp_path):
    pip = [sys.executable, "-m", "pip", "--disable-pip-version-check"]
    # No build isolation: scikit-build-core and pybind11 are installed by install-deps.sh,
    # and the test must not depend on the network.
    subprocess.run(pip + ["wheel", str(ROOT), "--no-build-isolation", "--no-deps", "-w",
                          str(tmp_path / "dist")], check=True, capture_output=True)
    wheels = list((tmp_path / "dist").glob("upkie_rl-*.whl"))
    assert len(wheels) == 1
    target = tmp_path / "site"
    subprocess.run(pip + ["install", "--no-deps", "--target", str(target), str(wheels[0])],
                   check=True, capture_output=True)
    assert (target / "upkie_rl" / "models" / "upkie" / "upkie.urdf").exists()
    script = (
        "import os, gymnasium as gym, numpy as np, upkie_rl\n"
        "assert upkie_rl.__file__.startswith(os.environ['TARGET']), upkie_rl.__file__\n"
        "assert os.environ['UPKIE_RL_MODEL'].startswith(os.environ['TARGET'])\n"
        "env = gym.make('Upkie-Bullet-Pendulum')\n"
        "observation, info = env.reset(seed=0)\n"
        "observation, reward, *_ = env.step(np.zeros(1, dtype=np.float32))\n"
        "venv = upkie_rl.make_vec('upkie_rl/Upkie-Mock-Pendulum', 2)\n"
        "venv.reset()\n"
        "print(reward)\n"
    )
    environment = {key: value for key, value in os.environ.items()
                   if key not in ("PYTHONPATH", "UPKIE_RL_MODEL")}
    environment.update(PYTHONPATH=str(target), TARGET=str(target))
    result = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=environment,
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert 0.0 < float(result.stdout.strip()) <= 1.0
    # The extension does not link libtorch.
    module = next((target / "upkie_rl").glob("_core*.so"))
    linked = subprocess.run(["ldd", str(module)], capture_output=True, text=True).stdout
    assert "libtorch" not in linked and "libc10" not in linked
