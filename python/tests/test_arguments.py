"""The package's own keyword arguments (counts, seeds, frame sizes, indices, flags, episodes)
are checked before they reach the bindings: one line naming the argument, its value and its
range, the C++ declarations' range, instead of pybind11's four-line "incompatible function
arguments" or a run that never ends."""

import subprocess

import gymnasium as gym
import numpy as np
import pytest

import upkie_rl
from upkie_rl import _core
from spine_process import cli_path

ENV_ID = "Upkie-Mock-Pendulum"
SEED_MAX = 2**64 - 1


class ZeroPolicy:
    """Acts 0 on every observation: evaluate() needs only check_env and a call."""

    def check_env(self, env):
        pass

    def __call__(self, observation):
        return np.zeros(1, dtype=np.float32)


CASES = [
    # (call, exception, text the one-line message holds)
    (lambda: upkie_rl.make_vec(ENV_ID, 2, num_threads=2**70), ValueError,
     "num_threads: 1180591620717411303424 is outside [0, 256]"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2**64), ValueError,
     "num_envs: 18446744073709551616 is outside [1, 4096]"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2.5), TypeError,
     "num_envs: 2.5 is not an integer; expected one in [1, 4096]"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2, seed=-1), ValueError,
     f"seed: -1 is outside [0, {SEED_MAX}]"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2, seed=2**70), ValueError, "seed: 1180591620717411303424"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2).reset(seed=2**80), ValueError,
     "seed: 1208925819614629174706176 is outside"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2).reset(seed="1"), TypeError, "seed: '1' is not an integer"),
    (lambda: gym.make(f"upkie_rl/{ENV_ID}").reset(seed=2**80), ValueError,
     "seed: 1208925819614629174706176 is outside"),
    (lambda: gym.make(f"upkie_rl/{ENV_ID}").reset(seed=-1), ValueError, "seed: -1 is outside"),
    (lambda: gym.make(f"upkie_rl/{ENV_ID}", render_mode="rgb_array", render_width=2**40),
     ValueError, "render_width: 1099511627776 is outside [16, 1920]"),
    (lambda: gym.make(f"upkie_rl/{ENV_ID}", render_mode="rgb_array", render_height=float("nan")),
     TypeError, "render_height: nan is not an integer; expected one in [16, 1080]"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2, render_mode="rgb_array", render_width=float("nan")),
     TypeError, "render_width: nan is not an integer"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2, render_mode="rgb_array", render_envs=10**12),
     ValueError, "render_envs: 1000000000000 is outside [1, 4096]"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2).spine_observation(-1), IndexError,
     "index: -1 is outside [0, 1]"),
    (lambda: upkie_rl.make_vec(ENV_ID, 2, spine_observation="yes"), TypeError,
     "spine_observation: 'yes' is not a bool"),
    (lambda: gym.make(f"upkie_rl/{ENV_ID}", render_overlay=1), TypeError,
     "render_overlay: 1 is not a bool"),
    (lambda: upkie_rl.make_sb3_vec_env(ENV_ID, 2, seed=-1), ValueError, "seed: -1 is outside"),
    (lambda: upkie_rl.make_sb3_vec_env(ENV_ID, 2).env_method("spine_observation", indices=-1),
     IndexError, "index: -1 is outside [0, 1]"),
    (lambda: upkie_rl.evaluate(ZeroPolicy(), ENV_ID, episodes=10**12), ValueError,
     "episodes: 1000000000000 is outside [1, 1000000]"),
    (lambda: upkie_rl.evaluate(ZeroPolicy(), ENV_ID, episodes=0), ValueError,
     "episodes: 0 is outside [1, 1000000]"),
    (lambda: upkie_rl.evaluate(ZeroPolicy(), ENV_ID, episodes=-1), ValueError,
     "episodes: -1 is outside"),
    (lambda: upkie_rl.evaluate(ZeroPolicy(), ENV_ID, episodes=float("nan")), TypeError,
     "episodes: nan is not an integer"),
    (lambda: upkie_rl.evaluate(ZeroPolicy(), ENV_ID, seed=2**80), ValueError,
     "seed: 1208925819614629174706176 is outside"),
    (lambda: upkie_rl.evaluate(ZeroPolicy(), ENV_ID, exact_start="no"), TypeError,
     "exact_start: 'no' is not a bool"),
]


@pytest.mark.parametrize("call, error, text", CASES, ids=[c[2][:40] for c in CASES])
def test_a_bad_argument_gets_one_line_naming_it(call, error, text):
    with pytest.raises(error) as raised:
        call()
    message = str(raised.value)
    assert text in message
    assert "\n" not in message and "incompatible function arguments" not in message


def test_python_and_cpp_report_a_count_alike():
    """One range, one wording: the package's check and make_vector_env's say the same."""
    with pytest.raises(ValueError) as python_side:
        upkie_rl.make_vec(ENV_ID, 4097)
    with pytest.raises(ValueError) as cpp_side:
        _core.VectorEnv(ENV_ID, [], 4097, 0)
    assert str(python_side.value) == str(cpp_side.value) == "num_envs: 4097 is outside [1, 4096]"


def test_evaluate_episodes_bound_is_the_command_lines():
    low, high = _core.ARGUMENT_RANGES["episodes"]
    command = [str(cli_path()), "evaluate", "--env", ENV_ID, "--controller", "zero"]
    for episodes in (low - 1, high + 1):
        refused = subprocess.run(
            command + ["--episodes", str(episodes)], capture_output=True, text=True
        )
        assert refused.returncode != 0
        # The command line names the flag and the value it refuses.
        assert f"--episodes: {episodes} " in refused.stderr


def test_numpy_integers_and_the_largest_seed_are_accepted():
    venv = upkie_rl.make_vec(ENV_ID, num_envs=np.int64(2), seed=np.uint64(SEED_MAX))
    observations, _ = venv.reset()
    assert observations.shape == (2, 4)
    # Episode seeds wrap around past the largest, as the command line's 64-bit ones.
    with pytest.warns(UserWarning, match="identical"):  # the mock's start has no noise
        results = upkie_rl.evaluate(ZeroPolicy(), ENV_ID, episodes=2, seed=SEED_MAX)
    assert len(results) == 2
