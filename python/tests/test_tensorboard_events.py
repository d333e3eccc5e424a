"""TensorBoard itself reads the event files `upkie-rl train` writes, with SB3's tag names."""

import csv
import os
import subprocess
from pathlib import Path

from tensorboard.backend.event_processing import event_accumulator

SB3_TAGS = {
    "train/loss",
    "train/policy_gradient_loss",
    "train/value_loss",
    "train/entropy_loss",
    "train/approx_kl",
    "train/clip_fraction",
    "train/explained_variance",
    "train/learning_rate",
    "train/std",
    "train/clip_range",
    "rollout/ep_rew_mean",
    "rollout/ep_len_mean",
    "time/fps",
}


def cli_path() -> Path:
    return Path(os.environ.get("UPKIE_RL_BUILD_DIR", "build")) / "upkie-rl"


def test_tensorboard_reads_training_events(tmp_path):
    run_dir = tmp_path / "run"
    config = Path(__file__).resolve().parents[2] / "configs" / "pendulum.yaml"
    subprocess.run(
        [
            str(cli_path()), "train", "--config", str(config), "--run-dir", str(run_dir),
            "--set", "env.id=Upkie-Mock-Pendulum", "--set", "env.num_envs=2",
            "--set", "env.threads=0", "--set", "ppo.total_timesteps=6144",
        ],
        check=True, capture_output=True, timeout=300,
    )
    accumulator = event_accumulator.EventAccumulator(
        str(run_dir), size_guidance={event_accumulator.SCALARS: 0}
    )
    accumulator.Reload()
    tags = set(accumulator.Tags()["scalars"])
    assert SB3_TAGS <= tags, f"missing tags: {sorted(SB3_TAGS - tags)}"

    with open(run_dir / "progress.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    losses = accumulator.Scalars("train/loss")
    assert len(losses) == len(rows) == 3  # 6144 steps / 2048 per update
    assert [event.step for event in losses] == [int(row["time/total_timesteps"]) for row in rows]
    for event, row in zip(losses, rows):
        assert abs(event.value - float(row["train/loss"])) <= 1e-5 * max(1.0, abs(event.value))
