"""upkie_rl vector environments: Gymnasium VectorEnv and SB3 VecEnv stepped in C++, equal to
the single environments, deterministic for any thread count, with the GIL released."""

import threading
import time

import gymnasium as gym
import numpy as np
import pytest

import upkie_rl
from upkie_rl.env import UpkieEnv

ENV_ID = "Upkie-Bullet-Pendulum"
# Random initial pitches and random actions: episodes end at different steps, by falls.
OPTIONS = dict(init_rand_pitch=0.3, max_episode_steps=60)


def random_actions(num_steps, num_envs, seed=0):
    return np.random.default_rng(seed).uniform(-1, 1, (num_steps, num_envs, 1)).astype(
        np.float32)


def single_env_rollout(num_envs, actions, seed):
    """What num_envs single environments give, auto-reset in the same step (unseeded)."""
    envs = [UpkieEnv(ENV_ID, **OPTIONS) for _ in range(num_envs)]
    observations = [env.reset(seed=seed + i)[0] for i, env in enumerate(envs)]
    steps = []
    for row in actions:
        step = {"obs": [], "rew": [], "term": [], "trunc": [], "final": {}}
        for i, env in enumerate(envs):
            observation, reward, terminated, truncated, _ = env.step(row[i])
            if terminated or truncated:
                step["final"][i] = observation
                observation, _ = env.reset()
            step["obs"].append(observation)
            step["rew"].append(np.float32(reward))
            step["term"].append(terminated)
            step["trunc"].append(truncated)
        steps.append(step)
    return np.array(observations), steps


@pytest.mark.parametrize("num_threads", [0, 1, 2, 3])
def test_same_step_vector_equals_single_envs(num_threads):
    num_envs, seed = 3, 11
    actions = random_actions(150, num_envs)
    first, expected = single_env_rollout(num_envs, actions, seed)
    venv = upkie_rl.make_vec(ENV_ID, num_envs, num_threads=num_threads, seed=seed,
                             autoreset_mode="SameStep", **OPTIONS)
    observations, _ = venv.reset()
    np.testing.assert_array_equal(observations, first)
    endings = 0
    for row, step in zip(actions, expected):
        observations, rewards, terminated, truncated, infos = venv.step(row)
        np.testing.assert_array_equal(observations, np.array(step["obs"]))
        np.testing.assert_array_equal(rewards, np.array(step["rew"], dtype=np.float64))
        np.testing.assert_array_equal(terminated, step["term"])
        np.testing.assert_array_equal(truncated, step["trunc"])
        for i, final in step["final"].items():
            assert infos["_final_obs"][i]
            np.testing.assert_array_equal(infos["final_obs"][i], final)
            endings += 1
    assert endings >= 3  # the test saw auto-resets


def test_next_step_autoreset_is_gymnasiums():
    venv = upkie_rl.make_vec(ENV_ID, 2, num_threads=0, seed=0, **OPTIONS)
    mode = venv.metadata["autoreset_mode"]
    assert getattr(mode, "value", mode) == "NextStep"
    assert isinstance(venv, gym.vector.VectorEnv)
    venv.reset()
    zero = np.zeros((2, 1), dtype=np.float32)
    ended = np.zeros(2, dtype=bool)
    for _ in range(200):
        observations, rewards, terminated, truncated, _ = venv.step(zero)
        if ended.any():
            # The step after an episode's end resets it: reward 0, flags false.
            assert np.all(rewards[ended] == 0.0)
            assert not terminated[ended].any() and not truncated[ended].any()
            np.testing.assert_allclose(observations[ended][:, [1, 3]], 0.0, atol=1e-6)
            break
        ended = terminated | truncated
    else:
        pytest.fail("no episode ended")


def test_results_do_not_depend_on_the_thread_count():
    actions = random_actions(100, 4, seed=1)
    runs = []
    for num_threads in (0, 2, 4):
        venv = upkie_rl.make_vec(ENV_ID, 4, num_threads=num_threads, seed=7, **OPTIONS)
        observations = [venv.reset()[0]]
        observations += [venv.step(row)[0] for row in actions]
        runs.append(np.array(observations))
    np.testing.assert_array_equal(runs[0], runs[1])
    np.testing.assert_array_equal(runs[0], runs[2])


def test_gym_make_vec_uses_the_vector_entry_point():
    venv = gym.make_vec(ENV_ID, num_envs=4, vectorization_mode="vector_entry_point",
                        fall_pitch=0.5, num_threads=2)
    assert isinstance(venv.unwrapped, upkie_rl.UpkieVectorEnv)
    assert venv.num_envs == 4 and venv.unwrapped.num_threads == 2
    assert venv.observation_space.shape == (4, 4)
    assert venv.single_action_space.shape == (1,)
    observations, _ = venv.reset(seed=0)
    assert observations.dtype == np.float32 and observations.shape == (4, 4)
    _, rewards, terminated, truncated, _ = venv.step(np.zeros((4, 1), dtype=np.float32))
    assert rewards.shape == (4,) and terminated.dtype == bool
    venv.close()
    namespaced = gym.make_vec(f"upkie_rl/{ENV_ID}", num_envs=2,
                              vectorization_mode="vector_entry_point")
    assert isinstance(namespaced.unwrapped, upkie_rl.UpkieVectorEnv)


def test_sb3_vec_env_semantics():
    vec_env = pytest.importorskip("stable_baselines3.common.vec_env")
    VecEnv, VecNormalize = vec_env.VecEnv, vec_env.VecNormalize
    num_envs, seed = 3, 11
    actions = random_actions(150, num_envs)
    first, expected = single_env_rollout(num_envs, actions, seed)
    venv = upkie_rl.make_sb3_vec_env(ENV_ID, num_envs, num_threads=2, seed=seed, **OPTIONS)
    assert isinstance(venv, VecEnv)
    np.testing.assert_array_equal(venv.reset(), first)
    for row, step in zip(actions, expected):
        observations, rewards, dones, infos = venv.step(row)
        np.testing.assert_array_equal(observations, np.array(step["obs"]))
        np.testing.assert_array_equal(rewards, np.array(step["rew"]))
        for i in range(num_envs):
            if dones[i]:
                np.testing.assert_array_equal(infos[i]["terminal_observation"],
                                              step["final"][i])
                assert infos[i]["TimeLimit.truncated"] == (step["trunc"][i]
                                                           and not step["term"][i])
                assert infos[i]["episode"]["l"] > 0
            else:
                assert infos[i] == {}
    # VecEnv.seed applies at the next reset, env i with seed + i.
    venv.seed(seed)
    np.testing.assert_array_equal(venv.reset(), first)
    normalized = VecNormalize(venv, norm_obs=True, norm_reward=True, clip_obs=10.0)
    assert normalized.reset().shape == (num_envs, 4)


def test_vector_bad_input_raises_clear_exceptions():
    venv = upkie_rl.make_vec(ENV_ID, 2, num_threads=2, seed=0)
    with pytest.raises(RuntimeError, match="before reset"):
        venv.step(np.zeros((2, 1), dtype=np.float32))
    venv.reset()
    with pytest.raises(ValueError, match=r"actions has shape \(3, 1\), expected \(2, 1\)"):
        venv.step(np.zeros((3, 1), dtype=np.float32))
    with pytest.raises(ValueError, match="ground_velocity"):
        venv.step(np.array([[0.0], [np.nan]], dtype=np.float32))
    with pytest.raises(TypeError, match="real numbers"):
        venv.step(np.array([["a"], ["b"]]))
    with pytest.raises(ValueError, match="num_envs"):
        upkie_rl.make_vec(ENV_ID, 0)
    with pytest.raises(ValueError, match="autoreset_mode"):
        upkie_rl.make_vec(ENV_ID, 2, autoreset_mode="Sometimes")
    with pytest.raises(ValueError, match="unknown option"):
        upkie_rl.make_vec(ENV_ID, 2, fall_pich=1.0)
    observations, *_ = venv.step(np.zeros((2, 1)))  # still usable
    assert observations.shape == (2, 4)


def test_spine_observations_only_when_asked():
    quiet = upkie_rl.make_vec(ENV_ID, 2, num_threads=0)
    quiet.reset()
    assert quiet.step(np.zeros((2, 1), dtype=np.float32))[-1] == {}
    verbose = upkie_rl.make_vec(ENV_ID, 2, num_threads=0, spine_observation=True)
    verbose.reset()
    infos = verbose.step(np.zeros((2, 1), dtype=np.float32))[-1]
    assert infos["spine_observation"][1]["servo"]["left_wheel"]["position"] is not None


def test_the_gil_is_released_while_envs_step():
    """Two Python threads stepping two vector envs: their step calls overlap in time. With
    the GIL held during a step, calls could only overlap by the few bytecodes between a
    call's return and its end timestamp (microseconds), not by most of a step (ms)."""
    intervals = {0: [], 1: []}
    envs = [upkie_rl.make_vec(ENV_ID, 8, num_threads=0, seed=i) for i in range(2)]
    zero = np.zeros((8, 1), dtype=np.float32)
    barrier = threading.Barrier(2)

    def run(index):
        env = envs[index]
        env.reset()
        barrier.wait()
        for _ in range(60):
            start = time.perf_counter()
            env.step(zero)
            intervals[index].append((start, time.perf_counter()))

    threads = [threading.Thread(target=run, args=(i,)) for i in range(2)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    overlap = sum(
        max(0.0, min(a_end, b_end) - max(a_start, b_start))
        for a_start, a_end in intervals[0]
        for b_start, b_end in intervals[1]
    )
    busy = sum(end - start for start, end in intervals[0])
    assert overlap > 0.25 * busy, f"step calls overlapped {overlap:.4f} s of {busy:.4f} s"
