"""The installed wheel on its own (`make test-wheel`, scripts/wheels/test.sh): run by the
venv's interpreter from a folder outside the repository, with the package from the venv's
site-packages and nothing of the source tree importable. Each test checks what a Python
user who has never built C++ relies on: every id passes Gymnasium's checker, vector envs,
rendering (and a clear error without EGL), trained policies, the SB3 converter and a short
SB3 PPO training (when SB3 is installed in the venv).

UPKIE_RL_WHEEL_TEST_POLICIES names the folder of the checked-in policies the runner copied
(tests/data/policies)."""

import os
import subprocess
import sys
import sysconfig
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import upkie_rl

SITE_PACKAGES = Path(sysconfig.get_paths()["purelib"]).resolve()
PACKAGE_DIR = Path(upkie_rl.__file__).resolve().parent
POLICIES = Path(os.environ.get("UPKIE_RL_WHEEL_TEST_POLICIES", "policies"))
# The ids that need no external process (the Spine ids talk to a spine's shared memory).
LOCAL_IDS = [env_id for env_id in upkie_rl.registered_env_ids() if "-Spine-" not in env_id]
# What a manylinux wheel may take from the system (auditwheel's policy); everything else
# must come from the wheel (upkie_rl.libs) or from the mujoco wheel.
SYSTEM_LIBRARIES = ("linux-vdso", "libc.so", "libm.so", "libstdc++.so", "libgcc_s.so",
                    "libpthread.so", "libdl.so", "librt.so", "ld-linux-x86-64.so", "libz.so")


def test_the_package_is_the_installed_wheel_not_a_source_tree():
    assert PACKAGE_DIR.parent == SITE_PACKAGES, PACKAGE_DIR
    assert not any(Path(entry, "CMakeLists.txt").exists() for entry in sys.path if entry)
    assert (PACKAGE_DIR / "models" / "upkie" / "upkie.urdf").exists()
    assert os.environ["UPKIE_RL_MODEL"] == str(PACKAGE_DIR / "models" / "upkie" / "upkie.urdf")


def test_the_extension_needs_only_the_wheels_and_the_base_system():
    (module,) = PACKAGE_DIR.glob("_core*.so")
    listing = subprocess.run(["ldd", str(module)], capture_output=True, text=True, check=True)
    assert "not found" not in listing.stdout, listing.stdout
    for line in listing.stdout.splitlines():
        name = Path(line.strip().split()[0]).name
        target = line.split("=>")[1].split("(")[0].strip() if "=>" in line else name
        inside = target.startswith(str(SITE_PACKAGES)) or target.startswith(str(PACKAGE_DIR.parent))
        assert inside or name.startswith(SYSTEM_LIBRARIES), line
        assert "torch" not in name and "libc10" not in name and "libEGL" not in name, line
    assert "upkie_rl.libs" in listing.stdout  # auditwheel's copies: Bullet, urdfdom, ...
    assert "mujoco/libmujoco.so" in listing.stdout


def test_every_copied_library_has_its_copyright_and_license():
    licenses = PACKAGE_DIR / "third_party_licenses"
    listing = (licenses / "README.txt").read_text()
    libraries = sorted((PACKAGE_DIR.parent / "upkie_rl.libs").glob("*.so*"))
    assert len(libraries) >= 10  # Bullet (3), urdfdom, ONNX (2), protobuf, yaml-cpp, ...
    for library in libraries:
        (line,) = [line for line in listing.splitlines() if f"/{library.name}:" in line]
        license_file = licenses / line.rsplit(", ", 1)[1]
        assert license_file.stat().st_size > 500, license_file
    for header_only in ("libeigen3-dev", "nlohmann-json3-dev", "pybind11"):
        assert header_only in listing


@pytest.mark.parametrize("env_id", LOCAL_IDS)
def test_gymnasium_checker_passes(env_id):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # infinite bounds, non-normalised Boxes
        check_env(gym.make(f"upkie_rl/{env_id}").unwrapped, skip_render_check=True)


def test_every_id_of_every_backend_is_registered():
    ids = set(upkie_rl.registered_env_ids())
    for backend in ("Bullet", "MuJoCo", "Mock", "Spine"):
        for task in ("Servos", "Pendulum", "Gyropod", "ServosTask", "Velocity"):
            assert f"Upkie-{backend}-{task}" in ids
            assert f"upkie_rl/Upkie-{backend}-{task}" in gym.registry


def test_vector_env_steps_its_environments_apart():
    venv = upkie_rl.make_vec("Upkie-MuJoCo-Pendulum", num_envs=4, num_threads=2, seed=0)
    observations, _ = venv.reset(seed=0)
    assert observations.shape == (4, 4) and observations.dtype == np.float32
    actions = np.linspace(-1.0, 1.0, 4, dtype=np.float32).reshape(4, 1)
    for _ in range(20):
        observations, rewards, terminated, truncated, _ = venv.step(actions)
    assert rewards.shape == (4,) and np.all(np.isfinite(observations))
    # Different actions drive the copies apart: no environment is another's alias.
    assert len({tuple(row) for row in observations.round(6)}) == 4
    venv.close()


@pytest.mark.parametrize("backend", ["MuJoCo", "Bullet"])
def test_a_rendered_frame_shows_the_robot(backend):
    env = gym.make(f"upkie_rl/Upkie-{backend}-Pendulum", render_mode="rgb_array",
                   render_width=320, render_height=240)
    env.reset(seed=0)
    frame = env.render()
    assert frame.shape == (240, 320, 3) and frame.dtype == np.uint8
    # Not blank: many colours (floor, sky, robot), no single one covering the frame.
    colours, counts = np.unique(frame.reshape(-1, 3), axis=0, return_counts=True)
    assert len(colours) > 50, len(colours)
    assert counts.max() < 0.9 * 240 * 320
    assert frame.std() > 10.0
    env.close()


def test_without_egl_rendering_raises_a_clear_error_and_the_rest_works():
    script = (
        "import gymnasium as gym, numpy as np, upkie_rl\n"
        "env = gym.make('upkie_rl/Upkie-MuJoCo-Pendulum', render_mode='rgb_array')\n"
        "env.reset(seed=0)\n"
        "env.step(np.zeros(1, dtype=np.float32))\n"
        "try:\n"
        "    env.render()\n"
        "except upkie_rl.RenderError as error:\n"
        "    print('RenderError:', error)\n"
    )
    environment = dict(os.environ, UPKIE_RL_EGL_LIBRARY="libEGL-missing-for-this-test.so.1")
    result = subprocess.run([sys.executable, "-c", script], env=environment,
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert "RenderError: cannot load libEGL-missing-for-this-test.so.1" in result.stdout
    assert "libegl-mesa0" in result.stdout and "mesa-libEGL" in result.stdout


def test_a_checked_in_policy_balances_the_pendulum():
    policy = upkie_rl.load_policy(POLICIES / "pendulum_bullet_seed0.ckpt")
    assert policy.env_id == "Upkie-Bullet-Pendulum"
    env = gym.make("Upkie-Bullet-Pendulum")
    observation, _ = env.reset(seed=0)
    steps = 0
    for steps in range(1, 301):
        action, state = policy.predict(observation, deterministic=True)
        assert state is None and action.shape == (1,) and action.dtype == np.float32
        observation, _, terminated, truncated, _ = env.step(action)
        assert not terminated, f"fell after {steps} steps"
        if truncated:
            break
    assert steps >= 300 or truncated
    batch, _ = policy.predict(np.zeros((8, 4), dtype=np.float32))
    assert batch.shape == (8, 1) and np.all(np.abs(batch) <= 1.0)
    with pytest.raises(FileNotFoundError):
        upkie_rl.load_policy(POLICIES / "no_such_model.ckpt")


def test_upkie_rl_command_says_training_needs_the_source_build():
    command = Path(sys.executable).parent / "upkie-rl"
    environment = dict(os.environ, PATH=str(command.parent))  # no other upkie-rl to defer to
    result = subprocess.run([str(command), "train", "--config", "pendulum.yaml"],
                            env=environment, capture_output=True, text=True)
    assert result.returncode == 2
    assert "source build" in result.stderr and "Stable-Baselines3" in result.stderr


# Run in a fresh interpreter: once Mesa's llvmpipe has rendered a frame in a process (the
# tests above), PyPI's triton, which SB3's PPO imports through torch._dynamo, segfaults
# as it loads its own LLVM; MuJoCo's own renderer does the same (docs/wheels.md, "Known
# problems").
SB3_SCRIPT = """
import sys
from pathlib import Path
import numpy as np
import stable_baselines3
import stable_baselines3.common.logger
import upkie_rl
from upkie_rl.sb3_convert import export_sb3, import_sb3

work, policies = Path(sys.argv[1]), Path(sys.argv[2])
venv = upkie_rl.make_sb3_vec_env("Upkie-Bullet-Pendulum", num_envs=2, seed=0)
model = stable_baselines3.PPO("MlpPolicy", venv, n_steps=128, batch_size=64, n_epochs=2,
                              seed=0, device="cpu")
# SB3 otherwise makes an empty SB3-<date> directory in /tmp at every learn().
model.set_logger(stable_baselines3.common.logger.configure(str(work / "sb3_log"), [""]))
model.learn(total_timesteps=512)
assert model.num_timesteps >= 512, model.num_timesteps
model.save(work / "ppo.zip")
imported = import_sb3(work / "ppo.zip", "Upkie-Bullet-Pendulum", work / "ppo.ckpt")
policy = upkie_rl.load_policy(imported)
observations = np.random.default_rng(0).normal(0, 0.1, (16, 4)).astype(np.float32)
ours, _ = policy.predict(observations, deterministic=True)
theirs, _ = model.predict(observations, deterministic=True)
np.testing.assert_allclose(ours, theirs, atol=1e-6)
assert np.ptp(ours) > 0  # the observations give different actions
# And back: a checked-in upkie-rl policy as an SB3 model that PPO.load reads.
export_sb3(policies / "pendulum_bullet_seed0.ckpt", work / "exported.zip",
           work / "vecnormalize.pkl")
exported = stable_baselines3.PPO.load(work / "exported.zip", device="cpu")
assert exported.observation_space.shape == (4,)
print("sb3 ok", model.num_timesteps)
"""


def test_sb3_ppo_trains_and_its_model_converts_to_an_upkie_rl_policy(tmp_path):
    pytest.importorskip("stable_baselines3", reason="SB3 is not installed in this venv")
    result = subprocess.run(
        [sys.executable, "-c", SB3_SCRIPT, str(tmp_path), str(POLICIES.resolve())],
        capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr[-3000:]
    assert "sb3 ok 512" in result.stdout
