#!/usr/bin/env python3
"""The ES158 lab's pendulum training with Stable-Baselines3, on upkie-rl's C++ environments.

Trains SB3 PPO with the seed's configuration: 10 environments, VecNormalize (observations
and rewards, clip 10, gamma 0.99), separate 64x64 ReLU actor and critic, learning rate
linear from 2e-4 to 1e-5, 2,048 steps per update, batch 128, 5 epochs, clip 0.2 (value clip
0.2), no entropy bonus, value coefficient 0.5, max gradient norm 0.5, checkpoints (model and
normalisation statistics) every 50,000 steps. Then evaluates 10 deterministic episodes
with the frozen statistics and prints the mean return, the lengths, the wall time and the
training steps per second.

    PYTHONPATH=build/python python3 examples/train_pendulum_sb3.py   # upkie-rl, 1M steps
    python3 examples/train_pendulum_sb3.py --backend upkie           # public upkie + PyBullet
    ... --total-timesteps 20000 --num-envs 10 --threads 2 --seed 0 --output DIR --json PATH

Writes DIR/checkpoints/pendulum_<N>_steps.zip and pendulum_vecnormalize_<N>_steps.pkl,
then DIR/model_<time>.zip and DIR/vecnormalize_<time>.pkl; ``--json`` also writes the summary
(steps/s, returns, lengths, paths). On this 2-core machine the 1M-step run takes 11:14 on
upkie-rl (1,485 steps/s, mean return 297.4, every episode 300 steps); the public package
steps about 440/s (its first 100,000 steps), so about 38 min for 1M.

``--backend upkie`` runs the same training on the public ``upkie`` package's
Upkie-PyBullet-Pendulum (needs ``pip install upkie pybullet``), wrapped with the seed's
reward and terminations as the lab does, in ``SubprocVecEnv`` processes (it keeps one
PyBullet connection per process); it is there to compare the two.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import gymnasium as gym
import numpy as np
import torch
from stable_baselines3 import PPO
from stable_baselines3.common.callbacks import CheckpointCallback
from stable_baselines3.common.vec_env import DummyVecEnv, SubprocVecEnv, VecNormalize

ENV_ID = "Upkie-Bullet-Pendulum"
PUBLIC_ENV_ID = "Upkie-PyBullet-Pendulum"


def linear_schedule(initial: float, final: float):
    """SB3 schedule: ``progress_remaining`` goes from 1 to 0 during training."""
    return lambda progress_remaining: final + progress_remaining * (initial - final)


class SeedPendulumTask(gym.Wrapper):
    """The seed's pendulum task (reward eq. 9, terminations of section 1.5, truncation at 300
    steps) around the public upkie Upkie-*-Pendulum, whose own reward and termination differ.
    upkie-rl's environments have it built in."""

    WEIGHTS = dict(theta=2.0, theta_dot=0.5, p_dot=0.5, a=1.0, s=2.0, accel=1.5)

    def __init__(self, env: gym.Env, max_steps: int = 300):
        super().__init__(env)
        self.max_steps = max_steps

    def reset(self, **kwargs):
        observation, info = self.env.reset(**kwargs)
        self.p0 = float(observation[1])
        self.last_action = self.last_delta = 0.0
        self.steps = 0
        return observation, info

    def step(self, action):
        observation, _, _, _, info = self.env.step(action)
        theta, p, theta_dot, p_dot = (float(x) for x in observation)
        a = float(np.clip(action, self.action_space.low, self.action_space.high)[0])
        delta = a - self.last_action
        accel = delta - self.last_delta
        self.last_action, self.last_delta = a, delta
        w = self.WEIGHTS
        reward = 1.0 - (w["theta"] * theta**2 + w["theta_dot"] * theta_dot**2
                        + w["p_dot"] * p_dot**2 + w["a"] * a**2 + w["s"] * delta**2
                        + w["accel"] * accel**2)
        terminated = (abs(theta) > 1.0 or abs(p - self.p0) > 5.0 or abs(theta_dot) > 10.0
                      or abs(p_dot) > 2.0)
        self.steps += 1
        truncated = self.steps >= self.max_steps
        return observation, reward, terminated, truncated, info


def make_public_env():
    """One public Upkie-PyBullet-Pendulum (headless, 200 Hz, a_max 1 m/s) with the seed's task.

    ``regulate_frequency=False``: upkie's default (True) sleeps so that every env steps at
    most at 200 Hz of wall time, which would cap ten envs at 2,000 steps/s and measure the
    clock rather than the simulation.
    """
    import upkie.envs

    upkie.envs.register()
    env = gym.make(PUBLIC_ENV_ID, frequency=200.0, max_ground_velocity=1.0, gui=False,
                   regulate_frequency=False)
    return SeedPendulumTask(env)


def make_training_env(backend: str, num_envs: int, threads: int, seed: int):
    if backend == "upkie_rl":
        import upkie_rl

        return upkie_rl.make_sb3_vec_env(ENV_ID, num_envs, num_threads=threads, seed=seed)
    venv = SubprocVecEnv([make_public_env for _ in range(num_envs)])
    venv.seed(seed)
    return venv


def make_evaluation_env(backend: str):
    if backend == "upkie_rl":
        import upkie_rl  # noqa: F401 (registers the ids)

        return DummyVecEnv([lambda: gym.make(ENV_ID)])
    return SubprocVecEnv([make_public_env])  # its own process: one PyBullet connection


def evaluate(model: PPO, statistics: Path, backend: str, episodes: int):
    """Deterministic episodes with the frozen normalisation: (returns, lengths)."""
    venv = VecNormalize.load(str(statistics), make_evaluation_env(backend))
    venv.training = False
    venv.norm_reward = False
    returns, lengths = [], []
    observation = venv.reset()
    total, length = 0.0, 0
    while len(returns) < episodes:
        action, _ = model.predict(observation, deterministic=True)
        observation, reward, done, _ = venv.step(action)
        total += float(venv.get_original_reward()[0])
        length += 1
        if done[0]:
            returns.append(total)
            lengths.append(length)
            total, length = 0.0, 0
    venv.close()
    return returns, lengths


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--backend", choices=("upkie_rl", "upkie"), default="upkie_rl")
    parser.add_argument("--total-timesteps", type=int, default=1_000_000)
    parser.add_argument("--num-envs", type=int, default=10)
    parser.add_argument("--threads", type=int, default=2, help="upkie_rl: stepping threads")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--episodes", type=int, default=10, help="evaluation episodes")
    parser.add_argument("--checkpoint-every", type=int, default=50_000)
    parser.add_argument("--torch-threads", type=int, default=1)
    parser.add_argument("--device", default="cpu", help="torch device (the MLP is small)")
    parser.add_argument("--output", type=Path, default=Path("runs/sb3_pendulum"))
    parser.add_argument("--json", type=Path, help="write the summary there too")
    args = parser.parse_args()

    # One thread: the 64x64 MLPs are too small for torch's thread pool to pay off.
    torch.set_num_threads(args.torch_threads)
    args.output.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    venv = VecNormalize(
        make_training_env(args.backend, args.num_envs, args.threads, args.seed),
        norm_obs=True, norm_reward=True, clip_obs=10.0, clip_reward=10.0, gamma=0.99,
    )
    model = PPO(
        "MlpPolicy", venv,
        learning_rate=linear_schedule(2e-4, 1e-5),
        n_steps=2048 // args.num_envs, batch_size=128, n_epochs=5, gamma=0.99,
        gae_lambda=0.95, clip_range=0.2, clip_range_vf=0.2, ent_coef=0.0, vf_coef=0.5,
        max_grad_norm=0.5,
        policy_kwargs=dict(net_arch=dict(pi=[64, 64], vf=[64, 64]),
                           activation_fn=torch.nn.ReLU),
        seed=args.seed, device=args.device, verbose=0,
    )
    checkpoints = CheckpointCallback(
        save_freq=max(1, args.checkpoint_every // args.num_envs),
        save_path=str(args.output / "checkpoints"), name_prefix="pendulum",
        save_vecnormalize=True,
    )
    model.learn(total_timesteps=args.total_timesteps, callback=checkpoints)
    train_time = time.perf_counter() - start  # environment creation included
    stamp = time.strftime("%Y%m%d-%H%M%S")
    model_path = args.output / f"model_{stamp}.zip"
    statistics = args.output / f"vecnormalize_{stamp}.pkl"
    model.save(str(model_path))
    venv.save(str(statistics))
    venv.close()

    eval_start = time.perf_counter()
    returns, lengths = evaluate(model, statistics, args.backend, args.episodes)
    eval_time = time.perf_counter() - eval_start
    summary = {
        "backend": args.backend,
        "num_envs": args.num_envs,
        "seed": args.seed,
        "torch_threads": args.torch_threads,
        "total_timesteps": int(model.num_timesteps),
        "train_seconds": train_time,
        "steps_per_second": model.num_timesteps / train_time,
        "mean_return": float(np.mean(returns)),
        "std_return": float(np.std(returns)),
        "mean_length": float(np.mean(lengths)),
        "eval_seconds": eval_time,
        "wall_seconds": time.perf_counter() - start,
        "returns": returns,
        "lengths": lengths,
        "model": str(model_path),
        "vecnormalize": str(statistics),
        "checkpoints": sorted(str(p) for p in (args.output / "checkpoints").glob("*.zip")),
    }
    print(f"{args.backend}: trained {model.num_timesteps:,} steps in {train_time:.1f} s "
          f"({summary['steps_per_second']:,.0f} steps/s)")
    print(f"evaluation: mean return {summary['mean_return']:.1f} +- {summary['std_return']:.1f}"
          f" over {len(returns)} episodes from the environment's own start (no"
          f" initial-state randomisation), lengths {lengths}")
    print(f"wall time {summary['wall_seconds']:.1f} s (evaluation {eval_time:.1f} s)")
    if args.json:
        args.json.write_text(json.dumps(summary, indent=2))


if __name__ == "__main__":
    main()
