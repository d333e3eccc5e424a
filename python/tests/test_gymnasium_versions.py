"""The package on every Gymnasium from 1.0 to the newest that pyproject.toml allows.

`make test-python` runs this suite twice: with Gymnasium 1.0.0 (Debian's interpreter) and
with the newest release in the venv of scripts/install-deps.sh. Gymnasium 1.1 made
``metadata["autoreset_mode"]`` an ``AutoresetMode`` enum that its vector wrappers require;
a string there crashed them.
"""

import re
import sys
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import upkie_rl

ENV_ID = "Upkie-Bullet-Pendulum"
PYPROJECT = Path(__file__).resolve().parents[2] / "pyproject.toml"


def version_tuple(text):
    return tuple(int(part) for part in re.findall(r"\d+", text)[:3])


def test_the_running_gymnasium_is_in_the_declared_range():
    if sys.version_info < (3, 11):
        pytest.skip("tomllib needs Python 3.11")
    import tomllib

    dependencies = tomllib.loads(PYPROJECT.read_text())["project"]["dependencies"]
    (requirement,) = [d for d in dependencies if d.startswith("gymnasium")]
    lower = re.search(r">=\s*([\d.]+)", requirement)
    upper = re.search(r"<\s*([\d.]+)", requirement)
    assert lower and upper, f"{requirement}: the range must have both bounds"
    running = version_tuple(gym.__version__)
    assert version_tuple(lower.group(1)) <= running < version_tuple(upper.group(1)), (
        gym.__version__, requirement)


@pytest.mark.parametrize("name", ["NextStep", "SameStep"])
def test_autoreset_mode_is_gymnasiums_enum_where_it_exists(name):
    enum = getattr(gym.vector, "AutoresetMode", None)
    venv = upkie_rl.make_vec(ENV_ID, 2, num_threads=0, autoreset_mode=name)
    mode = venv.metadata["autoreset_mode"]
    if enum is None:  # Gymnasium 1.0: a name
        assert mode == name
    else:
        assert isinstance(mode, enum) and mode == enum(name)
        # The enum itself is accepted too.
        again = upkie_rl.make_vec(ENV_ID, 2, num_threads=0, autoreset_mode=enum(name))
        assert again.metadata["autoreset_mode"] is mode
    venv.close()


def test_disabled_autoreset_is_refused_with_the_valid_modes():
    enum = getattr(gym.vector, "AutoresetMode", None)
    mode = "Disabled" if enum is None else enum.DISABLED
    with pytest.raises(ValueError, match="NextStep"):
        upkie_rl.make_vec(ENV_ID, 2, autoreset_mode=mode)


def test_gymnasium_vector_wrappers_step_the_vector_env():
    """RecordEpisodeStatistics (checks the autoreset enum from 1.1 on) and NormalizeReward
    (reads it) over both modes, through gym.make_vec."""
    for name in ("NextStep", "SameStep"):
        venv = gym.make_vec(ENV_ID, num_envs=3, vectorization_mode="vector_entry_point",
                            autoreset_mode=name, init_rand_pitch=0.3, max_episode_steps=40)
        venv = gym.wrappers.vector.RecordEpisodeStatistics(venv)
        venv = gym.wrappers.vector.NormalizeReward(venv)
        venv.reset(seed=0)
        episodes = 0
        for _ in range(120):
            _, rewards, _, _, infos = venv.step(np.zeros((3, 1), dtype=np.float32))
            assert rewards.shape == (3,) and np.all(np.isfinite(rewards))
            if "episode" in infos:
                episodes += int(infos["_episode"].sum())
        assert episodes >= 3, name
        venv.close()


def test_single_env_passes_the_checker_of_this_gymnasium():
    from gymnasium.utils.env_checker import check_env

    env = gym.make(f"upkie_rl/{ENV_ID}")
    check_env(env.unwrapped, skip_render_check=True)
    env.close()
