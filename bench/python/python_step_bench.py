"""Environment steps per second from Python, beside `upkie-rl bench` for the same setup.

Runs, alternately and ``--repeats`` times each: `upkie-rl bench` (C++ only), the Gymnasium
single environment (``gym.make``, with and without building ``info``), and the vector env
(``upkie_rl.make_vec``), all under the pendulum's linear law v = 10 theta + p + 0.1 p_dot
computed as the CLI computes it, so that all of them step the same trajectories. Prints a table and,
with ``--json``, one JSON line.

    PYTHONPATH=build/python python3 bench/python/python_step_bench.py --steps 3000
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import time
from pathlib import Path

import gymnasium as gym
import numpy as np

import upkie_rl

GAINS = np.array([10.0, 1.0, 0.0, 0.1], dtype=np.float32)


def linear_law(observations: np.ndarray) -> np.ndarray:
    """The CLI's `linear:10,1,0,0.1` in its float32 operations and order, so that Python and
    C++ step the very same trajectories (the physics' cost depends on the state)."""
    velocity = np.zeros(observations.shape[:-1], dtype=np.float32)
    for k in range(4):
        velocity = velocity + GAINS[k] * observations[..., k]
    return np.clip(velocity, -1.0, 1.0).astype(np.float32)[..., None]


def cli_bench(cli: Path, env_id: str, num_envs: int, threads: int, steps: int) -> float:
    command = [
        str(cli), "bench", "--env", env_id, "--num-envs", str(num_envs),
        "--threads", str(threads), "--steps", str(steps),
        "--controller", "linear:10,1,0,0.1", "--json",
    ]
    output = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    return json.loads(output.strip().splitlines()[-1])["env_steps_per_s"]


def single_env(env_id: str, steps: int, with_info: bool) -> float:
    env = gym.make(env_id, disable_env_checker=True, spine_observation=with_info)
    observation, _ = env.reset(seed=0)
    start = time.perf_counter()
    for _ in range(steps):
        observation, _, terminated, truncated, _ = env.step(linear_law(observation))
        if terminated or truncated:
            observation, _ = env.reset()
    return steps / (time.perf_counter() - start)


def vector_env(env_id: str, num_envs: int, threads: int, steps: int) -> float:
    venv = upkie_rl.make_vec(env_id, num_envs, num_threads=threads, seed=0,
                             autoreset_mode="SameStep")
    observations, _ = venv.reset()
    start = time.perf_counter()
    for _ in range(steps):
        observations, *_ = venv.step(linear_law(observations))
    return steps * num_envs / (time.perf_counter() - start)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--env", default="Upkie-Bullet-Pendulum")
    parser.add_argument("--steps", type=int, default=3000)
    parser.add_argument("--num-envs", type=int, default=10)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--cli", type=Path, default=Path("build/upkie-rl"))
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    vector_steps = max(1, args.steps // args.num_envs)
    figures = {key: [] for key in (
        "cli_single", "python_single", "python_single_no_info", "cli_vector", "python_vector")}
    for _ in range(args.repeats):
        figures["cli_single"].append(cli_bench(args.cli, args.env, 1, 0, args.steps))
        figures["python_single"].append(single_env(args.env, args.steps, True))
        figures["python_single_no_info"].append(single_env(args.env, args.steps, False))
        figures["cli_vector"].append(
            cli_bench(args.cli, args.env, args.num_envs, args.threads, vector_steps))
        figures["python_vector"].append(
            vector_env(args.env, args.num_envs, args.threads, vector_steps))
    medians = {key: statistics.median(values) for key, values in figures.items()}
    ratios = {
        "single_with_info": medians["python_single"] / medians["cli_single"],
        "single_without_info": medians["python_single_no_info"] / medians["cli_single"],
        "vector": medians["python_vector"] / medians["cli_vector"],
    }
    for key, values in figures.items():
        print(f"{key:24s} median {medians[key]:9.0f} env steps/s  runs "
              + ", ".join(f"{v:.0f}" for v in values))
    for key, value in ratios.items():
        print(f"ratio {key:24s} {100 * value:5.1f}%")
    if args.json:
        print(json.dumps({"medians": medians, "runs": figures, "ratios": ratios}))


if __name__ == "__main__":
    main()
