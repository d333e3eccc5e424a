"""Stable-Baselines3 interoperability: a PPO trained by SB3 on upkie_rl.make_sb3_vec_env
with VecNormalize, imported, acts in `upkie-rl rollout` as PPO.predict does (actions within
1e-5, same returns); exporting back gives a zip SB3 loads with the same predictions; the
provenance survives both ways; malformed or hostile zips and pickles are refused without
running anything they contain."""

import io
import json
import os
import pickle
import subprocess
import sys
import zipfile
from pathlib import Path

import numpy as np
import pytest

pytestmark = pytest.mark.needs_torch_numpy  # conftest.py

import upkie_rl
from spine_process import cli_path

sb3 = pytest.importorskip("stable_baselines3")
torch = pytest.importorskip("torch")
from stable_baselines3.common.logger import configure as configure_sb3_logger  # noqa: E402
from stable_baselines3.common.vec_env import VecNormalize  # noqa: E402

from upkie_rl.safe_pickle import UnsafePickleError  # noqa: E402
from upkie_rl.sb3_convert import (  # noqa: E402
    ConversionError,
    describe_sb3,
    export_sb3,
    import_sb3,
)

ENV_ID = "Upkie-Bullet-Pendulum"
POLICIES = Path(__file__).resolve().parents[2] / "tests" / "data" / "policies"
EPISODES, SEED = 2, 11


def convert(*arguments):
    """Runs `python3 -m upkie_rl.sb3_convert ...` as a user would."""
    return subprocess.run([sys.executable, "-m", "upkie_rl.sb3_convert", *map(str, arguments)],
                          capture_output=True, text=True, env=os.environ.copy())


@pytest.fixture(scope="module", params=["Tanh", "ReLU"])
def sb3_model(request, tmp_path_factory):
    """A tiny PPO (1,024 steps) trained by SB3 with VecNormalize, saved as users save it."""
    directory = tmp_path_factory.mktemp(f"sb3_{request.param}")
    venv = VecNormalize(upkie_rl.make_sb3_vec_env(ENV_ID, num_envs=2, seed=0))
    model = sb3.PPO("MlpPolicy", venv, n_steps=256, batch_size=64, n_epochs=2, seed=0,
                    device="cpu", policy_kwargs={"net_arch": [32, 32],
                                                 "activation_fn": getattr(torch.nn, request.param)})
    # SB3 otherwise makes an empty SB3-<date> directory in /tmp at every learn().
    model.set_logger(configure_sb3_logger(str(directory / "sb3_log"), [""]))
    model.learn(total_timesteps=1024)
    model.save(directory / "ppo.zip")
    venv.save(directory / "vecnormalize.pkl")
    venv.close()
    imported = directory / "imported.ckpt"
    result = convert("import", directory / "ppo.zip", "--env", ENV_ID,
                     "--vecnormalize", directory / "vecnormalize.pkl", "--output", imported)
    assert result.returncode == 0, result.stderr
    return directory, imported


def load_sb3(directory, zip_name="ppo.zip", statistics="vecnormalize.pkl"):
    model = sb3.PPO.load(directory / zip_name, device="cpu")
    venv = upkie_rl.make_sb3_vec_env(ENV_ID, num_envs=1)
    normalize = VecNormalize.load(str(directory / statistics), venv)
    normalize.training = False
    return model, normalize


def drive(actor):
    """Actions and returns of `actor` (observation -> action) driving the environment,
    episode e seeded SEED + e."""
    import gymnasium as gym

    env = gym.make(f"upkie_rl/{ENV_ID}")
    actions, returns = [], []
    for episode in range(EPISODES):
        observation, _ = env.reset(seed=SEED + episode)
        total, done = 0.0, False
        while not done:
            action = actor(observation)
            actions.append(action)
            observation, reward, terminated, truncated, _ = env.step(action)
            total += reward
            done = terminated or truncated
        returns.append(total)
    env.close()
    return np.array(actions), returns


def sb3_episodes(model, normalize):
    """Actions and returns of PPO.predict on the environment."""
    return drive(lambda observation: model.predict(normalize.normalize_obs(observation[None]),
                                                   deterministic=True)[0][0])


def cli_episodes(model_path, tmp_path):
    """Observations, actions and returns of `upkie-rl rollout --model` (its --record CSV
    writes each step's observation and action with 9 significant digits: float32 exactly)."""
    record = tmp_path / "rollout.csv"
    output = subprocess.run(
        [str(cli_path()), "rollout", "--env", ENV_ID, "--model", str(model_path),
         "--episodes", str(EPISODES), "--seed", str(SEED), "--record", str(record), "--json",
         "--exact-start"],  # PPO.predict's gym.make episodes start exactly upright
        check=True, capture_output=True, text=True).stdout
    summary = json.loads(output.strip().splitlines()[-1])
    lines = record.read_text().splitlines()
    header = lines[0].split(",")
    rows = np.array([[float(value) for value in line.split(",")[: len(header)]]
                     for line in lines[1:]], dtype=np.float64)
    observations = rows[:, 3:7].astype(np.float32)  # theta, p, theta_dot, p_dot
    actions = rows[:, [i for i, name in enumerate(header) if name.startswith("action.")]]
    return observations, actions.astype(np.float32), summary["returns"]


def test_imported_model_acts_in_upkie_rl_rollout_as_ppo_predict(sb3_model, tmp_path):
    directory, imported = sb3_model
    model, normalize = load_sb3(directory)
    observations, actions, returns = cli_episodes(imported, tmp_path)
    # Every action of the CLI rollout is PPO.predict's for the observation it acted on.
    predicted, _ = model.predict(normalize.normalize_obs(observations), deterministic=True)
    np.testing.assert_allclose(actions, predicted, rtol=0, atol=1e-5)
    # The Python policy of the imported file gives the CLI's returns exactly.
    results = upkie_rl.evaluate(upkie_rl.load_policy(imported), ENV_ID, EPISODES, SEED,
                                exact_start=True)
    assert [total for total, _ in results] == returns


def replay_returns(actions_by_episode):
    """Returns of the environment driven open loop by recorded actions (episode e seeded
    SEED + e, as in sb3_episodes and the CLI rollout)."""
    import gymnasium as gym

    env = gym.make(f"upkie_rl/{ENV_ID}")
    returns = []
    for episode, actions in enumerate(actions_by_episode):
        env.reset(seed=SEED + episode)
        total = 0.0
        for action in actions:
            # Added one by one as the episodes add them: Python 3.12's sum() compensates
            # its rounding (Neumaier) and gives another last bit over 300 rewards.
            total += env.step(action)[1]
        returns.append(total)
    env.close()
    return returns


def float64_actions(model, normalize, observations):
    """PPO's deterministic actions computed in float64 from the same float32 weights and
    float32 network input: the reference both float32 evaluations round from."""
    network = torch.nn.Sequential(*model.policy.mlp_extractor.policy_net,
                                  model.policy.action_net)
    inputs = torch.as_tensor(normalize.normalize_obs(observations)).float().double()
    with torch.no_grad():
        for layer in network:
            inputs = torch.nn.functional.linear(inputs, layer.weight.double(),
                                                layer.bias.double()) \
                if isinstance(layer, torch.nn.Linear) else layer(inputs)
    return np.clip(inputs.numpy(), -1.0, 1.0)


def test_ppo_predict_and_the_imported_policy_differ_only_by_float32_rounding(tmp_path):
    """Why PPO.predict driving the environment and `upkie-rl rollout` of the same policy
    imported get returns 297.988 and 297.845 (docs/interop.md), checked step by step on a
    balancing policy (the test data's, through an SB3 zip and back):
    - on the same observations their actions differ by float32 rounding only: each is within
      1e-7 of the network evaluated in float64 (torch sums in float32, DeployedPolicy in
      double then rounds), and they differ by at most 1e-7 from each other;
    - the environment is not the cause: PPO.predict's actions replayed open loop give its
      returns exactly, and the CLI's recorded actions replayed give the CLI's exactly;
    - the closed loop amplifies rounding: moving the imported policy's actions by one float32
      ulp changes its return by more than the gap between the two;
    - so the returns agree within 0.1%, not bit for bit."""
    export_sb3(POLICIES / "pendulum_bullet_seed0.ckpt", tmp_path / "ppo.zip",
               tmp_path / "vecnormalize.pkl")
    imported = import_sb3(tmp_path / "ppo.zip", ENV_ID, tmp_path / "imported.ckpt",
                          tmp_path / "vecnormalize.pkl")
    model, normalize = load_sb3(tmp_path)
    expected_actions, expected_returns = sb3_episodes(model, normalize)
    observations, actions, returns = cli_episodes(imported, tmp_path)
    assert len(actions) == len(expected_actions) == EPISODES * 300
    # Same observations (the CLI's), both evaluations, and the float64 reference.
    predicted, _ = model.predict(normalize.normalize_obs(observations), deterministic=True)
    reference = float64_actions(model, normalize, observations)
    assert np.abs(predicted - actions).max() <= 1e-7
    assert np.abs(predicted - reference).max() <= 1e-7
    assert np.abs(actions - reference).max() <= 1e-7
    # Open-loop replays: each side's actions give its own returns exactly.
    steps = 300
    assert replay_returns(expected_actions.reshape(EPISODES, steps, -1)) == expected_returns
    assert replay_returns(actions.reshape(EPISODES, steps, -1)) == returns
    # One ulp on every action of the imported policy moves the return more than the gap.
    policy = upkie_rl.load_policy(imported)
    _, nudged = drive(lambda observation: np.nextafter(policy(observation), np.float32(np.inf)))
    gap = abs(returns[0] - expected_returns[0])
    assert 0 < gap < abs(nudged[0] - returns[0])
    np.testing.assert_allclose(returns, expected_returns, rtol=1e-3)


def test_imported_model_loads_in_python_and_says_where_it_came_from(sb3_model):
    directory, imported = sb3_model
    policy = upkie_rl.load_policy(imported)
    assert policy.env_id == ENV_ID
    model, normalize = load_sb3(directory)
    observations = np.random.default_rng(0).normal(0, 1, (500, 4)).astype(np.float32)
    expected, _ = model.predict(normalize.normalize_obs(observations), deterministic=True)
    np.testing.assert_allclose(policy(observations), expected, rtol=0, atol=1e-5)
    provenance = upkie_rl.model_provenance(imported)
    assert provenance["source"] == "upkie_rl.sb3_convert import"
    assert provenance["timesteps"] == 1024 and provenance["seed"] == 0
    assert provenance["imported_from"]["stable_baselines3_version"] == sb3.__version__
    assert provenance["env_id"] == ENV_ID


def test_export_round_trips_to_the_same_predictions_and_provenance(sb3_model, tmp_path):
    directory, imported = sb3_model
    result = convert("export", imported, "--output", tmp_path / "back.zip",
                     "--vecnormalize", tmp_path / "back.pkl")
    assert result.returncode == 0, result.stderr
    original, original_normalize = load_sb3(directory)
    back, back_normalize = load_sb3(tmp_path, "back.zip", "back.pkl")
    observations = np.random.default_rng(1).normal(0, 2, (500, 4)).astype(np.float32)
    expected, _ = original.predict(original_normalize.normalize_obs(observations), deterministic=True)
    actions, _ = back.predict(back_normalize.normalize_obs(observations), deterministic=True)
    np.testing.assert_allclose(actions, expected, rtol=0, atol=1e-5)
    described = describe_sb3(tmp_path / "back.zip")
    assert described["upkie_rl"]["provenance"]["imported_from"]["file"] == "ppo.zip"
    # Imported again, the model remembers its whole history.
    again = import_sb3(tmp_path / "back.zip", ENV_ID, tmp_path / "again.ckpt", tmp_path / "back.pkl")
    provenance = upkie_rl.model_provenance(again)
    assert provenance["original"]["imported_from"]["file"] == "ppo.zip"


def test_trained_upkie_rl_policy_exports_to_sb3(tmp_path):
    model_path = POLICIES / "pendulum_mujoco_seed0.ckpt"
    with pytest.raises(ConversionError, match="normalises observations"):
        export_sb3(model_path, tmp_path / "ppo.zip")
    export_sb3(model_path, tmp_path / "ppo.zip", tmp_path / "vecnormalize.pkl")
    model = sb3.PPO.load(tmp_path / "ppo.zip", device="cpu")
    normalize = VecNormalize.load(str(tmp_path / "vecnormalize.pkl"),
                                  upkie_rl.make_sb3_vec_env("Upkie-MuJoCo-Pendulum", num_envs=1))
    policy = upkie_rl.load_policy(model_path)
    observations = np.random.default_rng(2).normal(0, 1, (1000, 4)).astype(np.float32)
    actions, _ = model.predict(normalize.normalize_obs(observations), deterministic=True)
    np.testing.assert_allclose(actions, policy(observations), rtol=0, atol=1e-5)
    assert describe_sb3(tmp_path / "ppo.zip")["upkie_rl"]["env_id"] == "Upkie-MuJoCo-Pendulum"


@pytest.mark.parametrize("activation", ["Tanh", "ReLU", "ELU", "LeakyReLU", "SiLU", "GELU",
                                        "Sigmoid", "Softplus", "SELU"])
def test_every_supported_activation_converts_to_the_same_actions(activation, tmp_path):
    """An untrained PPO (standard normal weights, larger than SB3's initial ones, so that
    every layer works in its nonlinear range) through import, ONNX export and export back
    to SB3."""
    ort = pytest.importorskip("onnxruntime")
    venv = upkie_rl.make_sb3_vec_env(ENV_ID, num_envs=1)
    model = sb3.PPO("MlpPolicy", venv, device="cpu", seed=3,
                    policy_kwargs={"net_arch": [16, 8], "activation_fn": getattr(torch.nn, activation)})
    torch.manual_seed(5)
    with torch.no_grad():
        for parameter in model.policy.parameters():
            parameter.normal_(0.0, 1.0)
    model.save(tmp_path / "ppo.zip")
    imported = import_sb3(tmp_path / "ppo.zip", ENV_ID, tmp_path / "imported.ckpt")
    observations = np.random.default_rng(4).normal(0, 2, (500, 4)).astype(np.float32)
    expected, _ = model.predict(observations, deterministic=True)
    assert np.std(expected) > 0.05  # The actions vary: the comparison below means something.
    np.testing.assert_allclose(upkie_rl.load_policy(imported)(observations), expected, atol=1e-5)
    upkie_rl.export_onnx(imported, tmp_path / "policy.onnx")
    session = ort.InferenceSession(str(tmp_path / "policy.onnx"), providers=["CPUExecutionProvider"])
    (onnx_actions,) = session.run(None, {"observation": observations})
    # onnxruntime computes activations its own way: 1.32's ELU differs from torch's by up to
    # 1.1e-5 on these weights (one action of 500); a wrong graph is off by 1e-2 or more.
    np.testing.assert_allclose(onnx_actions, expected, atol=1e-4)
    export_sb3(imported, tmp_path / "back.zip")
    back, _ = sb3.PPO.load(tmp_path / "back.zip", device="cpu").predict(observations, deterministic=True)
    np.testing.assert_allclose(back, expected, atol=1e-5)


def test_an_activation_without_equivalent_is_refused(tmp_path):
    venv = upkie_rl.make_sb3_vec_env(ENV_ID, num_envs=1)
    sb3.PPO("MlpPolicy", venv, device="cpu",
            policy_kwargs={"activation_fn": torch.nn.Hardswish}).save(tmp_path / "ppo.zip")
    with pytest.raises(ConversionError, match="activation Hardswish has no upkie-rl equivalent"):
        import_sb3(tmp_path / "ppo.zip", ENV_ID, tmp_path / "out.ckpt")


# ---------------------------------------------------------------------------------------
# What cannot be converted, and hostile inputs


def rewrite_zip(source, target, change):
    """A copy of the zip `source` whose members pass through change(name, bytes)."""
    with zipfile.ZipFile(source) as original, zipfile.ZipFile(target, "w") as copy:
        for name in original.namelist():
            data = change(name, original.read(name))
            if data is not None:
                copy.writestr(name, data)
    return target


def edit_data(source, target, edit):
    def change(name, data):
        if name != "data":
            return data
        content = json.loads(data)
        edit(content)
        return json.dumps(content)

    return rewrite_zip(source, target, change)


def test_other_algorithms_policies_and_spaces_are_refused(sb3_model, tmp_path):
    directory, _ = sb3_model
    ppo = directory / "ppo.zip"
    cases = {
        "not a PPO model": edit_data(ppo, tmp_path / "a2c.zip", lambda d: d.pop("clip_range")),
        "policy class ActorCriticCnnPolicy": edit_data(
            ppo, tmp_path / "cnn.zip",
            lambda d: d["policy_class"].update(__init__="<function ActorCriticCnnPolicy.__init__>")),
        "only flat vectors": edit_data(
            ppo, tmp_path / "image.zip",
            lambda d: d["observation_space"].update(_shape="[3, 8, 8]")),
        "gSDE": edit_data(ppo, tmp_path / "sde.zip", lambda d: d.update(use_sde=True)),
    }
    for message, path in cases.items():
        with pytest.raises(ConversionError, match=message):
            import_sb3(path, ENV_ID, tmp_path / "out.ckpt")
    with pytest.raises(ConversionError, match="observation space has shape"):
        import_sb3(ppo, "Upkie-Bullet-Gyropod", tmp_path / "out.ckpt")
    with pytest.raises(ConversionError, match=r"action space.low\[0\] is -1.0, the environment.s -2.5"):
        import_sb3(ppo, ENV_ID, tmp_path / "out.ckpt",
                   env_options={"max_ground_velocity": "2.5"})
    assert not (tmp_path / "out.ckpt").exists()


def test_a_real_a2c_model_is_refused(tmp_path):
    venv = upkie_rl.make_sb3_vec_env(ENV_ID, num_envs=1)
    sb3.A2C("MlpPolicy", venv, device="cpu").save(tmp_path / "a2c.zip")
    result = convert("import", tmp_path / "a2c.zip", "--env", ENV_ID, "-o", tmp_path / "x.ckpt")
    assert result.returncode == 1
    assert "not a PPO model" in result.stderr and "a2c.zip" in result.stderr


def test_malformed_and_truncated_zips_are_refused(sb3_model, tmp_path):
    directory, _ = sb3_model
    whole = (directory / "ppo.zip").read_bytes()
    (tmp_path / "truncated.zip").write_bytes(whole[: len(whole) // 2])
    (tmp_path / "text.zip").write_bytes(b"not a zip at all")
    rewrite_zip(directory / "ppo.zip", tmp_path / "no_policy.zip",
                lambda name, data: None if name == "policy.pth" else data)
    rewrite_zip(directory / "ppo.zip", tmp_path / "bad_json.zip",
                lambda name, data: b"{not json" if name == "data" else data)
    rewrite_zip(directory / "ppo.zip", tmp_path / "bad_pth.zip",
                lambda name, data: data[:100] if name == "policy.pth" else data)
    # Half of the zip may still hold a nested zip's directory (policy.pth is one): then it
    # is refused for lacking SB3's members.
    truncated = "(not a readable zip|no 'data' member)"
    for name, message in (("truncated.zip", truncated), ("text.zip", "not a readable zip"),
                          ("no_policy.zip", "no 'policy.pth'"), ("bad_json.zip", "not JSON"),
                          ("bad_pth.zip", "not a plain tensor state dict")):
        with pytest.raises(ConversionError, match=f"{name}: .*{message}"):
            import_sb3(tmp_path / name, ENV_ID, tmp_path / "out.ckpt")


def test_a_zip_bomb_is_refused_before_it_is_expanded(tmp_path):
    with zipfile.ZipFile(tmp_path / "bomb.zip", "w", zipfile.ZIP_DEFLATED) as archive:
        archive.writestr("data", b"\0" * (65 << 20))
    with pytest.raises(ConversionError, match="expands to"):
        import_sb3(tmp_path / "bomb.zip", ENV_ID, tmp_path / "out.ckpt")


class Exploit:
    """Pickles to a call of os.system, as a hostile file would."""

    def __init__(self, marker):
        self.marker = marker

    def __reduce__(self):
        return (os.system, (f"touch {self.marker}",))


def test_hostile_pickles_run_nothing(sb3_model, tmp_path):
    directory, _ = sb3_model
    marker = tmp_path / "pwned"
    (tmp_path / "hostile.pkl").write_bytes(pickle.dumps(Exploit(marker)))
    with pytest.raises(UnsafePickleError, match="refusing to load (posix|os).system"):
        import_sb3(directory / "ppo.zip", ENV_ID, tmp_path / "out.ckpt", tmp_path / "hostile.pkl")
    # A policy.pth whose pickle calls os.system: torch's weights_only loader refuses it.
    buffer = io.BytesIO()
    torch.save({"log_std": Exploit(marker)}, buffer)
    rewrite_zip(directory / "ppo.zip", tmp_path / "hostile.zip",
                lambda name, data: buffer.getvalue() if name == "policy.pth" else data)
    with pytest.raises(ConversionError, match="not a plain tensor state dict"):
        import_sb3(tmp_path / "hostile.zip", ENV_ID, tmp_path / "out.ckpt")
    assert not marker.exists()
    truncated = (directory / "vecnormalize.pkl").read_bytes()[:200]
    (tmp_path / "truncated.pkl").write_bytes(truncated)
    with pytest.raises(UnsafePickleError, match="truncated.pkl"):
        import_sb3(directory / "ppo.zip", ENV_ID, tmp_path / "out.ckpt", tmp_path / "truncated.pkl")
