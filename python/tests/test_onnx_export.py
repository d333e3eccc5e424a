"""ONNX export of trained policies: onnxruntime runs the exported model and gives the
actions of the C++ DeployedPolicy (load_policy of the .ckpt) within 1e-5, on random
observations and on observations recorded along episodes; its metadata names the
environment, spaces, frequency and provenance."""

import json
import subprocess
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import upkie_rl
from spine_process import cli_path

ort = pytest.importorskip("onnxruntime")

POLICIES = Path(__file__).resolve().parents[2] / "tests" / "data" / "policies"
# Every trained policy of the test data (pendulum, servos-balance), and a velocity policy
# trained here (the test data has none).
CHECKPOINTS = sorted(POLICIES.glob("*.ckpt"))
CONFIGS = Path(__file__).resolve().parents[2] / "configs"
VELOCITY = "velocity_one_iteration"


def session_of(path):
    options = ort.SessionOptions()
    options.intra_op_num_threads = 1
    return ort.InferenceSession(str(path), options, providers=["CPUExecutionProvider"])


def random_observations(space, count, seed):
    """Observations spread over the space: uniform within finite bounds, wide normal draws
    (scale 3) where a bound is infinite."""
    rng = np.random.default_rng(seed)
    low, high = space.low.astype(np.float64), space.high.astype(np.float64)
    finite = np.isfinite(low) & np.isfinite(high)
    uniform = rng.uniform(np.where(finite, low, 0), np.where(finite, high, 1), (count, low.size))
    normal = rng.normal(0.0, 3.0, (count, low.size))
    return np.where(finite, uniform, normal).astype(np.float32)


def recorded_observations(policy, provenance, steps=300):
    """Observations of episodes run with the policy on its environment and options."""
    options = {key: json.loads(value) if value.replace(".", "", 1).isdigit() else value
               for key, value in provenance["env_options"].items()}
    env = gym.make(f"upkie_rl/{policy.env_id}", **options)
    observation, _ = env.reset(seed=3)
    observations = []
    for _ in range(steps):
        observations.append(observation)
        observation, _, terminated, truncated, _ = env.step(policy(observation))
        if terminated or truncated:
            observation, _ = env.reset()
    env.close()
    return np.array(observations, dtype=np.float32)


@pytest.fixture(scope="module")
def velocity_checkpoint(tmp_path_factory):
    """One PPO iteration of configs/velocity.yaml (about 10 s): a velocity policy with its
    observation normalisation, through `upkie-rl train` as a user makes one."""
    run_dir = tmp_path_factory.mktemp("velocity_run")
    subprocess.run(
        [str(cli_path()), "train", "--config", str(CONFIGS / "velocity.yaml"), "--quiet",
         "--set", "ppo.total_timesteps=1024", "--set", "ppo.n_steps=1024",
         "--set", "ppo.batch_size=512", "--set", "env.num_envs=2", "--set", "env.mix_envs=1",
         "--set", "env.threads=1",
         "--run-dir", str(run_dir)], check=True, capture_output=True)
    (checkpoint,) = run_dir.glob("model_*.ckpt")
    return checkpoint


@pytest.fixture(scope="module", params=CHECKPOINTS + [VELOCITY],
                ids=lambda param: param if param == VELOCITY else param.stem)
def exported(request, tmp_path_factory):
    checkpoint = (request.getfixturevalue("velocity_checkpoint") if request.param == VELOCITY
                  else request.param)
    onnx_path = tmp_path_factory.mktemp("onnx") / (checkpoint.stem + ".onnx")
    upkie_rl.export_onnx(checkpoint, onnx_path)
    return checkpoint, onnx_path


def test_test_data_has_the_pendulum_and_servos_policies():
    names = {path.stem for path in CHECKPOINTS}
    assert "pendulum_mujoco_seed0" in names and "servos_balance_mujoco_seed0" in names


def test_the_velocity_policy_is_one(velocity_checkpoint):
    policy = upkie_rl.load_policy(velocity_checkpoint)
    assert policy.env_id == "Upkie-MuJoCo-Velocity"
    # configs/velocity.yaml's observation_history 3: the last three observations of 23 (20
    # and the IMU's acceleration, observe_acceleration).
    assert policy.observation_space.shape == (69,) and policy.action_space.shape == (6,)


def test_one_float_input_with_free_batch_and_one_output(exported):
    checkpoint, onnx_path = exported
    policy = upkie_rl.load_policy(checkpoint)
    session = session_of(onnx_path)
    (observation,) = session.get_inputs()
    (action,) = session.get_outputs()
    assert observation.name == "observation" and observation.type == "tensor(float)"
    assert observation.shape == ["batch", policy.observation_space.shape[0]]
    assert action.name == "action" and action.shape == ["batch", policy.action_space.shape[0]]


def test_metadata_names_environment_spaces_frequency_and_provenance(exported):
    checkpoint, onnx_path = exported
    policy = upkie_rl.load_policy(checkpoint)
    metadata = session_of(onnx_path).get_modelmeta().custom_metadata_map
    assert metadata["env_id"] == policy.env_id
    observation_space = json.loads(metadata["observation_space"])
    assert len(observation_space["low"]) == policy.observation_space.shape[0]
    assert len(json.loads(metadata["action_space"])["names"]) == policy.action_space.shape[0]
    assert float(metadata["frequency"]) > 0
    provenance = json.loads(metadata["provenance"])
    assert provenance["env_id"] == policy.env_id
    assert "seed" in provenance and "upkie_rl_version" in provenance and "config" in provenance


def test_random_observations_give_the_deployed_actions(exported):
    checkpoint, onnx_path = exported
    policy = upkie_rl.load_policy(checkpoint)
    observations = random_observations(policy.observation_space, 2000, seed=1)
    (actions,) = session_of(onnx_path).run(None, {"observation": observations})
    expected = policy(observations)
    assert actions.dtype == np.float32 and actions.shape == expected.shape
    np.testing.assert_allclose(actions, expected, rtol=0, atol=1e-5)
    # Clipping is inside: some actions of these wide draws sit on the bounds.
    assert np.all(actions <= policy.action_space.high) and np.all(actions >= policy.action_space.low)


def test_recorded_observations_give_the_deployed_actions(exported):
    checkpoint, onnx_path = exported
    policy = upkie_rl.load_policy(checkpoint)
    header = json.loads(upkie_rl._core.read_model_checkpoint(str(checkpoint))[0])
    provenance = json.loads(upkie_rl._core.model_provenance(json.dumps(header)))
    observations = recorded_observations(policy, provenance)
    session = session_of(onnx_path)
    (batch,) = session.run(None, {"observation": observations})
    np.testing.assert_allclose(batch, policy(observations), rtol=0, atol=1e-5)
    (single,) = session.run(None, {"observation": observations[:1]})
    np.testing.assert_allclose(single, batch[:1], rtol=0, atol=1e-6)


def test_a_damaged_model_is_refused_with_the_file_named(tmp_path):
    damaged = tmp_path / "damaged.ckpt"
    damaged.write_bytes(CHECKPOINTS[0].read_bytes()[:1000])
    with pytest.raises(ValueError, match="damaged.ckpt"):
        upkie_rl.export_onnx(damaged, tmp_path / "out.onnx")
    assert not (tmp_path / "out.onnx").exists()
