"""`upkie-rl spine --log`: the spine log read back by the `mpacklog` package (PyPI), the reader
Upkie's users have (`mpacklog.read_log`), as they read their robot's spine logs.

The public `upkie` package drives the spine for one simulated second; every logged
dictionary must hold the observation the agent received before a step and the servo
commands it sent for that step.
"""

import numpy as np
import pytest
from spine_process import SpineProcess, cli_path

gym = pytest.importorskip("gymnasium")
mpacklog = pytest.importorskip("mpacklog")
upkie_envs = pytest.importorskip("upkie.envs")

FREQUENCY = 200.0  # [Hz]
NB_STEPS = 200
JOINTS = {"left_hip", "left_knee", "left_wheel", "right_hip", "right_knee", "right_wheel"}


@pytest.fixture(scope="module", autouse=True)
def registered():
    if not cli_path().exists():
        pytest.skip(f"{cli_path()} not built")
    upkie_envs.register()


def test_spine_log_reads_back_with_mpacklog(tmp_path):
    log_path = tmp_path / "spine.mpack"
    spine = SpineProcess("--nb-substeps", "5", "--log", str(log_path))
    sent, seen = [], []
    try:
        env = gym.make("Upkie-Spine-Pendulum", shm_name=spine.shm_name, frequency=FREQUENCY,
                       regulate_frequency=False, frequency_checks=False)
        observation, info = env.reset(seed=0)
        for _ in range(NB_STEPS):
            seen.append(info["spine_observation"]["base_orientation"]["pitch"])
            theta, p, _, p_dot = observation
            action = np.clip([10.0 * theta + 1.0 * p + 0.1 * p_dot], -1.0, 1.0)
            observation, _, terminated, truncated, info = env.step(action)
            sent.append(info["spine_observation"]["servo"]["left_wheel"]["velocity"])
            assert not terminated
        env.close()
    finally:
        assert spine.stop() == 0
    entries = list(mpacklog.read_log(str(log_path)))
    assert len(entries) == NB_STEPS
    times = [entry["time"] for entry in entries]
    assert all(later > earlier for earlier, later in zip(times, times[1:]))
    for entry, pitch in zip(entries, seen):
        assert set(entry) == {"action", "observation", "time"}
        assert set(entry["action"]["servo"]) == JOINTS
        assert set(entry["observation"]["servo"]) == JOINTS
        assert entry["observation"]["base_orientation"]["pitch"] == pitch
        assert isinstance(entry["action"]["servo"]["left_wheel"]["velocity"], float)
    # The robot moved: the logged wheel commands are not all zero.
    assert max(abs(e["action"]["servo"]["left_wheel"]["velocity"]) for e in entries) > 0.1
