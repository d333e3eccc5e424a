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


def test_torchscript_and_checkpoint_give_the_same_actions(trained):
    pytest.importorskip("torch")
    checkpoint, torchscript, _ = trained
    native, scripted = upkie_rl.load_policy(checkpoint), upkie_rl.load_policy(torchscript)
    assert scripted.env_id == native.env_id
    np.testing.assert_array_equal(scripted.action_space.low, native.action_space.low)
    observations = np.random.default_rng(0).normal(0, 1, (64, 4)).astype(np.float32)
    batch = native(observations)
    assert batch.shape == (64, 1) and batch.dtype == np.float32
    np.testing.assert_allclose(scripted(observations), batch, atol=1e-5)
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
