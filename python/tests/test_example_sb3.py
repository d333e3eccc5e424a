"""The lab's SB3 workflow on upkie-rl (examples/train_pendulum_sb3.py): a short PPO run on
make_sb3_vec_env trains, checkpoints (model and VecNormalize statistics), saves its final
model, evaluates 10 deterministic episodes, writes its JSON summary, and beats a random
policy.

Reference returns on Upkie-Bullet-Pendulum through the example's own evaluation code
(frozen VecNormalize, 10-episode means as the example reports them):
- uniformly random actions in [-1, 1]: -1045 +- 170 per episode (300 episodes, 3 seeds; best
  episode -686, mean length about 200); its 10-episode means lie in [-1169, -968];
- the zero action: -61.2 (falls after 216 steps).
After 20,480 steps PPO is at about -100, so the bound below (-600) sits far from both.

Runs in well under a minute on 2 cores. Skips when upkie_rl (PYTHONPATH=build/python) or
stable_baselines3 cannot be imported.
"""

import importlib.util
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.needs_torch_numpy  # conftest.py

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "train_pendulum_sb3.py"
RANDOM_BEST_MEAN_RETURN = -968.0  # best 10-episode mean of a random policy (see above)
PASS_RETURN = -600.0


def _require(module: str) -> None:
    try:
        found = importlib.util.find_spec(module) is not None
    except (ImportError, ValueError):
        found = False
    if not found:
        pytest.skip(f"{module} cannot be imported (the example needs it)")
    try:
        __import__(module)
    except Exception as error:  # noqa: BLE001 (a broken build is a skip here, not a failure)
        pytest.skip(f"{module} cannot be imported: {error}")


def test_short_sb3_run_trains_checkpoints_and_beats_a_random_policy(tmp_path):
    _require("stable_baselines3")
    _require("upkie_rl")
    run_dir = tmp_path / "run"
    summary_path = tmp_path / "summary.json"
    result = subprocess.run(
        [sys.executable, str(EXAMPLE), "--backend", "upkie_rl", "--total-timesteps", "20480",
         "--checkpoint-every", "10000", "--seed", "0", "--output", str(run_dir),
         "--json", str(summary_path)],
        capture_output=True, text=True, env=dict(os.environ), timeout=600,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    assert "steps/s" in result.stdout and "mean return" in result.stdout, result.stdout

    summary = json.loads(summary_path.read_text())
    assert summary["backend"] == "upkie_rl"
    assert summary["total_timesteps"] >= 20480
    assert summary["steps_per_second"] > 0

    # Checkpoints every 10,000 steps, each with its normalisation statistics.
    checkpoints = sorted((run_dir / "checkpoints").glob("pendulum_*_steps.zip"))
    statistics = sorted((run_dir / "checkpoints").glob("pendulum_vecnormalize_*_steps.pkl"))
    assert len(checkpoints) >= 2 and len(statistics) == len(checkpoints), checkpoints
    assert [str(path) for path in checkpoints] == summary["checkpoints"]

    # The final model and its statistics.
    assert Path(summary["model"]).is_file() and Path(summary["vecnormalize"]).is_file()

    # Ten deterministic episodes of at most 300 steps, clearly better than random actions.
    assert len(summary["returns"]) == 10 and len(summary["lengths"]) == 10
    assert all(1 <= length <= 300 for length in summary["lengths"])
    assert summary["mean_return"] > PASS_RETURN > RANDOM_BEST_MEAN_RETURN, summary
