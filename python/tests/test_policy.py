"""Trained policies of `upkie-rl train` in Python: the .ckpt (C++, no torch) and the .pt
(TorchScript) give the same actions, and a Python rollout equals `upkie-rl rollout --model`."""

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

import upkie_rl
from spine_process import cli_path

ENV_ID = "Upkie-Bullet-Pendulum"
CONFIG = Path(__file__).resolve().parents[2] / "configs" / "pendulum.yaml"


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    """A short training run (4,096 steps): its final model and TorchScript export."""
    run_dir = tmp_path_factory.mktemp("run")
    subprocess.run(
        [str(cli_path()), "train", "--config", str(CONFIG), "--run-dir",
         str(run_dir), "--set", "ppo.total_timesteps=4096", "--set", "checkpoint_every=2048"],
        check=True, capture_output=True)
    (checkpoint,) = run_dir.glob("model_*.ckpt")
    (torchscript,) = run_dir.glob("model_*.pt")
    return checkpoint, torchscript, run_dir


def test_checkpoint_policy_matches_the_cli_rollout(trained):
    checkpoint, _, _ = trained
    policy = upkie_rl.load_policy(checkpoint)
    assert policy.env_id == ENV_ID
    assert policy.observation_space.shape == (4,) and policy.action_space.shape == (1,)
    results = upkie_rl.evaluate(policy, ENV_ID, episodes=2)
    output = subprocess.run(
        [str(cli_path()), "rollout", "--env", ENV_ID, "--model", str(checkpoint),
         "--episodes", "2", "--json"], check=True, capture_output=True, text=True).stdout
    summary = json.loads(output.strip().splitlines()[-1])
    assert [length for _, length in results] == summary["lengths"]
    np.testing.assert_allclose([total for total, _ in results], summary["returns"], rtol=1e-12)


@pytest.mark.needs_torch_numpy  # conftest.py
def test_torchscript_and_checkpoint_give_the_same_actions(trained):
    pytest.importorskip("torch")
    checkpoint, torchscript, _ = trained
    native, scripted = upkie_rl.load_policy(checkpoint), upkie_rl.load_policy(torchscript)
    assert scripted.env_id == native.env_id
    np.testing.assert_array_equal(scripted.action_space.low, native.action_space.low)
    observations = np.random.default_rng(0).normal(0, 1, (64, 4)).astype(np.float32)
    batch = native(observations)
    assert batch.shape == (64, 1) and batch.dtype == np.float32
    # The documented tolerance (docs/python.md): different float32 operation orders.
    difference = np.max(np.abs(scripted(observations) - batch))
    assert difference <= upkie_rl.PT_CKPT_TOLERANCE, difference
    np.testing.assert_array_equal(native(observations[3]), batch[3])
    assert np.all(np.abs(native(observations * 1e6)) <= 1.0)  # clipped to the bounds


def test_checkpoints_load_too_and_bad_files_name_the_problem(trained, tmp_path):
    _, _, run_dir = trained
    (checkpoint,) = (run_dir / "checkpoints").glob("*.ckpt")
    policy = upkie_rl.load_policy(checkpoint)
    assert policy(np.zeros(4, dtype=np.float32)).shape == (1,)
    with pytest.raises(FileNotFoundError, match="no policy file"):
        upkie_rl.load_policy(tmp_path / "missing.ckpt")
    garbage = tmp_path / "garbage.ckpt"
    garbage.write_bytes(b"model weights, honest")
    with pytest.raises(upkie_rl.CheckpointError, match="bad magic"):
        upkie_rl.load_policy(garbage)
    truncated = tmp_path / "truncated.ckpt"
    truncated.write_bytes(checkpoint.read_bytes()[:-100])
    with pytest.raises(ValueError, match="truncated.ckpt"):
        upkie_rl.load_policy(truncated)
    with pytest.raises(ValueError, match=r"observation has shape \(3,\)"):
        policy(np.zeros(3, dtype=np.float32))
    with pytest.raises(TypeError, match="real numbers"):
        policy(np.array(["a", "b", "c", "d"]))
    with pytest.raises(ValueError, match="observation_space"):
        policy.check_env(upkie_rl.UpkieEnv("Upkie-Bullet-Gyropod"))


def test_predict_is_sb3s_for_single_and_batched_observations(trained):
    checkpoint, _, _ = trained
    policy = upkie_rl.load_policy(checkpoint)
    observations = np.random.default_rng(1).normal(0, 0.1, (5, 4)).astype(np.float32)
    actions, state = policy.predict(observations)
    assert actions.shape == (5, 1) and state is None
    np.testing.assert_array_equal(actions, policy(observations))
    single, state = policy.predict(observations[2], deterministic=True)
    assert single.shape == (1,) and state is None
    np.testing.assert_array_equal(single, actions[2])
    # A recurrent state and episode starts pass through, as SB3's feed-forward policies do.
    marker = (np.zeros(3),)
    _, returned = policy.predict(observations, state=marker, episode_start=np.ones(5, bool))
    assert returned is marker
    with pytest.raises(ValueError, match="deterministic"):
        policy.predict(observations, deterministic=False)


def test_predict_works_with_sb3_evaluate_policy(trained):
    pytest.importorskip("stable_baselines3")
    from stable_baselines3.common.evaluation import evaluate_policy

    checkpoint, _, _ = trained
    policy = upkie_rl.load_policy(checkpoint)
    venv = upkie_rl.make_sb3_vec_env(ENV_ID, 2, seed=0)
    mean, std = evaluate_policy(policy, venv, n_eval_episodes=2)
    assert np.isfinite(mean) and std >= 0.0


def test_evaluations_start_from_a_random_state_unless_asked_for_the_exact_one(trained):
    checkpoint, _, _ = trained
    policy = upkie_rl.load_policy(checkpoint)
    added = dict(upkie_rl.evaluation_start_options(ENV_ID))
    assert added == {"init_rand_pitch": 0.05, "init_rand_omega_y": 0.1}, added
    # The user's own value wins.
    assert upkie_rl.evaluation_start_options(ENV_ID, {"init_rand_pitch": 0.2})[
        "init_rand_pitch"] == 0.2
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning: the episodes differ
        results = upkie_rl.evaluate(policy, ENV_ID, episodes=3)
    assert len({total for total, _ in results}) == 3, results
    with pytest.warns(UserWarning, match="all 3 episodes were identical"):
        exact = upkie_rl.evaluate(policy, ENV_ID, episodes=3, exact_start=True)
    assert len(set(exact)) == 1


def test_cli_rollout_starts_at_random_and_warns_for_identical_episodes(trained):
    checkpoint, _, _ = trained
    command = [str(cli_path()), "rollout", "--env", ENV_ID, "--model", str(checkpoint),
               "--episodes", "3", "--json"]
    random_start = subprocess.run(command, check=True, capture_output=True, text=True)
    assert "random initial state: init_rand_pitch=0.05 init_rand_omega_y=0.1" in (
        random_start.stdout)
    assert "identical" not in random_start.stderr
    assert len(set(json.loads(random_start.stdout.splitlines()[-1])["returns"])) == 3
    exact = subprocess.run(command + ["--exact-start"], check=True, capture_output=True,
                           text=True)
    assert "warning: all 3 episodes were identical" in exact.stderr, exact.stderr
