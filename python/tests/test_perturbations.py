"""Perturbation options from Python: keyword arguments of gym.make, flagged as
randomisation in the option table, seeded, and scaled by a curriculum."""

import gymnasium as gym
import numpy as np
import pytest

import upkie_rl
from upkie_rl import _core

PUSHED = dict(push_force=30.0, push_force_min=30.0, push_direction="forward",
              push_start=0.25, push_interval=0.2)


def episode(env, seed, steps=100):
    observation, _ = env.reset(seed=seed)
    observations = [observation]
    for _ in range(steps):
        action = np.clip(np.array([10.0 * observation[0] + observation[1] + 0.1 * observation[3]],
                                  dtype=np.float32), -1.0, 1.0)
        observation, _, terminated, truncated, _ = env.step(action)
        observations.append(observation)
        if terminated or truncated:
            break
    return np.array(observations)


def test_option_table_flags_randomisation():
    options = {o["name"]: o for o in _core.env_options("Upkie-MuJoCo-Pendulum")}
    for name in ("push_force", "inertia_variation", "init_rand_pitch", "observation_noise",
                 "action_delay"):
        assert options[name]["randomization"], name
    for name in ("frequency", "fall_pitch", "max_ground_velocity"):
        assert not options[name]["randomization"], name


def test_push_moves_the_robot_forward_and_seeds_repeat():
    pushed = gym.make("Upkie-MuJoCo-Pendulum", **PUSHED)
    nominal = gym.make("Upkie-MuJoCo-Pendulum")
    pushed_positions = episode(pushed, 3)[:, 1]
    nominal_positions = episode(nominal, 3)[:, 1]
    # The wheels roll forward to catch the pushed robot: p ends ahead of the nominal one.
    assert pushed_positions[-1] > nominal_positions[-1] + 0.01
    np.testing.assert_array_equal(episode(pushed, 3)[:, 1], pushed_positions)


def test_randomization_scale_zero_is_the_nominal_environment():
    env = gym.make("Upkie-MuJoCo-Pendulum", inertia_variation=0.3, observation_noise=0.01,
                   push_force=40.0, init_rand_pitch=0.2)
    env.unwrapped.set_randomization_scale(0.0)
    nominal = gym.make("Upkie-MuJoCo-Pendulum")
    np.testing.assert_array_equal(episode(env, 5), episode(nominal, 5))
    with pytest.raises(ValueError, match="randomization scale"):
        env.unwrapped.set_randomization_scale(2.0)
