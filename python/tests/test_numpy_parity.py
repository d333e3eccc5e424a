"""The Python package returns the C++ environments' numbers, element by element, under any
NumPy: observations, rewards, end flags, policy actions and rendered frames of every id,
against `python_parity_trace` (python/tests/parity/parity_trace.cpp), which makes the same
calls in C++ with no pybind11 and no NumPy in between.

Why: built against pybind11 2.10 (Debian's), the module ran under NumPy 2 and returned
observations whose every component was a copy of the first, with no error. `make
test-python` runs this file under Debian's NumPy 1.26 and under the newest NumPy 2 (the
newest-Gymnasium venv), so both interpreters are held to the same C++ numbers.
"""

import json
import os
import subprocess
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import upkie_rl

ROOT = Path(__file__).resolve().parents[2]
BUILD_DIR = Path(os.environ.get("UPKIE_RL_BUILD_DIR", ROOT / "build"))
TRACE = BUILD_DIR / "python_parity_trace"
POLICIES = ROOT / "tests" / "data" / "policies"
SEED = 3
STEPS = 120
FRAME_WIDTH, FRAME_HEIGHT = 96, 64

# Spine ids need a running spine: test_spine_upkie_pendulum.py covers them.
IDS = [i for i in upkie_rl.registered_env_ids() if "-Spine-" not in i]


def policy_for(env_id):
    """A checked-in policy whose observation space is the id's, if any."""
    if env_id.endswith("-Pendulum"):
        return POLICIES / "pendulum_mujoco_seed0.ckpt"
    # velocity_mujoco_seed0.ckpt observes the 20 components of the task before the height
    # command; the default velocity task (height_command=true) has 21: no policy fits it.
    return None


def cpp_trace(env_id, frame_path):
    command = [str(TRACE), env_id, str(SEED), str(STEPS)]
    policy = policy_for(env_id)
    if policy is not None:
        command += ["--policy", str(policy)]
    command += ["--frame", str(frame_path), str(FRAME_WIDTH), str(FRAME_HEIGHT)]
    done = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def scripted_action(low, high, step):
    """parity_trace.cpp's scripted_action: the same doubles, rounded to float32."""
    action = np.empty(len(low), dtype=np.float32)
    for i in range(len(low)):
        lo = float(low[i]) if np.isfinite(low[i]) else -1.0
        hi = float(high[i]) if np.isfinite(high[i]) else 1.0
        action[i] = np.float32(lo + ((7 * step + 3 * i) % 11) / 10.0 * (hi - lo))
    return action


class FlatView:
    """The user's env (gym.make) seen through flat float32 arrays: nested ids (Servos)
    take and give upkie's dictionaries, converted with the package's own layouts."""

    def __init__(self, env_id):
        self.env = gym.make("upkie_rl/" + env_id, render_mode="rgb_array", render_width=FRAME_WIDTH,
                            render_height=FRAME_HEIGHT, disable_env_checker=True)
        core = self.env.unwrapped._core
        self.low, self.high, _ = core.action_space
        self.neutral_action = core.neutral_action()
        self.observation_size = len(core.observation_space[0])
        self.observation_layout = self.env.unwrapped._observation_layout
        self.action_layout = self.env.unwrapped._action_layout

    def flat(self, observation):
        if self.observation_layout is None:
            return observation
        return self.observation_layout.to_flat(observation,
                                               np.zeros(self.observation_size, np.float32))

    def reset(self, seed=None):
        observation, _ = self.env.reset(seed=seed)
        return self.flat(observation)

    def step(self, flat_action):
        action = flat_action
        if self.action_layout is not None:
            action = self.action_layout.to_nested(flat_action)
        observation, reward, terminated, truncated, _ = self.env.step(action)
        return self.flat(observation), reward, terminated, truncated


def python_trace(env_id, policy):
    view = FlatView(env_id)
    out = {"observations": [], "rewards": [], "terminated": [], "truncated": [],
           "policy_actions": []}

    def record(observation):
        assert observation.dtype == np.float32 and observation.shape == (view.observation_size,)
        out["observations"].append(observation.copy())
        if policy is not None:
            action, _ = policy.predict(observation)
            out["policy_actions"].append(action)

    record(view.reset(seed=SEED))
    for step in range(STEPS):
        observation, reward, terminated, truncated = view.step(
            scripted_action(view.low, view.high, step))
        record(observation)
        out["rewards"].append(reward)
        out["terminated"].append(terminated)
        out["truncated"].append(truncated)
        if terminated or truncated:
            record(view.reset())
    frame = view.env.render()
    view.env.close()
    return out, frame


@pytest.mark.parametrize("env_id", IDS)
def test_python_returns_the_cpp_numbers(env_id, tmp_path):
    frame_path = tmp_path / "frame.rgb"
    expected = cpp_trace(env_id, frame_path)
    policy = policy_for(env_id)
    actual, frame = python_trace(env_id, upkie_rl.load_policy(policy) if policy else None)

    observations = np.array(expected["observations"], dtype=np.float32)
    assert len(actual["observations"]) == len(observations)
    np.testing.assert_array_equal(np.array(actual["observations"]), observations)
    # Not copies of one number (the NumPy 2 bug made every component a copy of the first):
    # a simulated robot's observations have different components (the mock's stay zero).
    if "-Mock-" not in env_id:
        assert any(len(np.unique(row)) > 1 for row in observations)
    np.testing.assert_array_equal(np.array(actual["rewards"]), np.array(expected["rewards"]))
    assert actual["terminated"] == expected["terminated"]
    assert actual["truncated"] == expected["truncated"]
    if policy is not None:
        np.testing.assert_array_equal(np.array(actual["policy_actions"]),
                                      np.array(expected["policy_actions"], dtype=np.float32))
    if frame_path.exists():
        reference = np.fromfile(frame_path, dtype=np.uint8).reshape(FRAME_HEIGHT, FRAME_WIDTH, 3)
        assert frame.dtype == np.uint8 and frame.shape == reference.shape
        assert frame.strides == (FRAME_WIDTH * 3, 3, 1)
        np.testing.assert_array_equal(frame, reference)
        assert len(np.unique(reference)) > 10  # a drawn robot, not a blank frame
    else:
        assert "-Mock-" in env_id  # only the mock has no simulator to draw


@pytest.mark.parametrize("env_id", ["Upkie-MuJoCo-Pendulum", "Upkie-Bullet-ServosTask"])
def test_vector_env_rows_are_the_single_envs(env_id):
    """Row i of a vector env seeded s is the env seeded s + i (EnvBatch::reset), so each
    row's numbers are checked against the single env, itself checked against C++ above."""
    num_envs = 3
    venv = upkie_rl.make_vec(env_id, num_envs=num_envs, num_threads=2, seed=SEED,
                             spine_observation=False)
    rows, _ = venv.reset(seed=SEED)
    for i in range(num_envs):
        view = FlatView(env_id)
        single = view.reset(seed=SEED + i)
        row = view.flat(_row_of(rows, i))
        np.testing.assert_array_equal(row, single)
        view.env.close()
    venv.close()


def _row_of(batched, i):
    """Row i of a batched nested observation."""
    if isinstance(batched, dict):
        return {key: _row_of(value, i) for key, value in batched.items()}
    return batched[i]


def test_numpy_reads_what_the_module_wrote():
    """The module's import check (numpy_layout_check.cpp) passed, and arrays it makes are
    C-ordered float32 with the strides NumPy expects."""
    env = upkie_rl._core.Env("Upkie-Mock-Pendulum")
    observation = env.reset(0)
    assert observation.dtype == np.float32
    assert observation.strides == (4,)
    assert observation.flags["C_CONTIGUOUS"] and observation.flags["OWNDATA"]
    low, high, names = env.observation_space
    assert low.strides == (4,) and len(names) == len(low)
