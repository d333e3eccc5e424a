"""Interoperability: the public `upkie` Python package as the agent of `upkie-rl spine`.

Its `Upkie-Spine-Pendulum` environment, driven by the linear feedback
v = 10 theta + 1 p + 0.1 p_dot, must keep the robot upright for 10 s of simulated
time on our spine, in both of its modes. Each test starts the spine process on a
unique shared-memory name and always stops it (SIGINT), checking that the spine
exits cleanly and removes its shared memory.
"""


import numpy as np
import pytest
from spine_process import SpineProcess, cli_path

gym = pytest.importorskip("gymnasium")
upkie_envs = pytest.importorskip("upkie.envs")

DURATION = 10.0  # [s]
FREQUENCY = 200.0  # [Hz]


@pytest.fixture(scope="module", autouse=True)
def registered():
    if not cli_path().exists():
        pytest.skip(f"{cli_path()} not built")
    upkie_envs.register()


def balance(spine: SpineProcess, regulate_frequency: bool):
    env = gym.make(
        "Upkie-Spine-Pendulum",
        shm_name=spine.shm_name,
        frequency=FREQUENCY,
        regulate_frequency=regulate_frequency,
        frequency_checks=False,
    )
    try:
        observation, info = env.reset(seed=0)
        spine_observation = info["spine_observation"]
        # The spine's dictionary, as the agent sees it.
        assert set(spine_observation["servo"]) == {
            "left_hip", "left_knee", "left_wheel",
            "right_hip", "right_knee", "right_wheel",
        }
        assert isinstance(spine_observation["base_orientation"]["pitch"], float)
        assert len(spine_observation["base_orientation"]["rotation_base_to_world"]) == 9
        assert spine_observation["time"] == 0.0
        max_pitch = 0.0
        nb_steps = int(DURATION * FREQUENCY)
        for _ in range(nb_steps):
            theta, p, theta_dot, p_dot = observation
            velocity = 10.0 * theta + 1.0 * p + 0.1 * p_dot
            action = np.clip([velocity], env.action_space.low, env.action_space.high)
            observation, _, terminated, truncated, info = env.step(action)
            assert not terminated, f"fell: {observation=}"
            max_pitch = max(max_pitch, abs(float(observation[0])))
        final_time = info["spine_observation"]["time"]
        return max_pitch, final_time, observation
    finally:
        env.close()


def test_pendulum_balances_on_request_spine():
    spine = SpineProcess("--nb-substeps", "5")
    try:
        max_pitch, final_time, observation = balance(spine, regulate_frequency=False)
    finally:
        returncode = spine.stop()
    assert returncode == 0
    # On request, each action is exactly 5 physics steps of 1 ms.
    assert final_time == pytest.approx(DURATION, abs=1e-9)
    assert max_pitch < 0.2
    assert abs(observation[1]) < 0.5  # stays near where it started


def test_pendulum_balances_on_real_time_spine():
    spine = SpineProcess("--spine-frequency", "1000")
    try:
        max_pitch, final_time, observation = balance(spine, regulate_frequency=True)
    finally:
        returncode = spine.stop()
    assert returncode == 0
    # Real time: the spine simulated (about) as long as the agent ran.
    assert final_time > 0.5 * DURATION
    assert max_pitch < 0.3


def test_request_codes_match_our_spine():
    """The installed upkie speaks the protocol our spine implements (spine.md)."""
    from upkie.envs.backends.spine.request import Request

    assert {r.name: int(r) for r in Request} == {
        "kNone": 0, "kAction": 1, "kStart": 2, "kStop": 3, "kError": 4,
    }


def test_spine_interrupted_while_waiting_cleans_up():
    spine = SpineProcess("--nb-substeps", "5")
    assert spine.process.poll() is None
    assert spine.stop() == 0
    assert not spine.shm_path.exists()
