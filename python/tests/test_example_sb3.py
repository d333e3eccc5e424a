"""The lab's SB3 workflow on upkie-rl (examples/train_pendulum_sb3.py): a short PPO run on
make_sb3_vec_env trains, checkpoints, evaluates, and beats a random policy.

A uniformly random policy on Upkie-Bullet-Pendulum returns -1041 +- 112 per episode (20
episodes, best -870, about 196 steps); the zero action -61 (216 steps). After about 20,000
steps PPO is at about -100, so the bound below leaves a wide margin on both sides.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "train_pendulum_sb3.py"
RANDOM_POLICY_BEST_RETURN = -870.0


def test_short_sb3_run_beats_a_random_policy(tmp_path):
    summary_path = tmp_path / "summary.json"
    environment = dict(os.environ)
    result = subprocess.run(
        [sys.executable, str(EXAMPLE), "--total-timesteps", "20480", "--checkpoint-every",
         "10000", "--output", str(tmp_path / "run"), "--json", str(summary_path)],
        capture_output=True, text=True, env=environment, timeout=600,
    )
    assert result.returncode == 0, result.stderr[-3000:]
    summary = json.loads(summary_path.read_text())
    assert summary["backend"] == "upkie_rl"
    assert summary["total_timesteps"] >= 20480
    assert len(summary["returns"]) == 10
    assert Path(summary["model"]).exists() and Path(summary["vecnormalize"]).exists()
    assert len(summary["checkpoints"]) >= 2  # every 10,000 steps
    assert summary["mean_return"] > RANDOM_POLICY_BEST_RETURN + 300.0, summary
    assert "steps/s" in result.stdout
