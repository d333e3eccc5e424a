"""UpkieSB3VecEnv: n C++ environments as a Stable-Baselines3 ``VecEnv``.

Importing this module imports stable_baselines3. Semantics are SB3's: same-step reset,
``infos[i]["terminal_observation"]`` and ``infos[i]["TimeLimit.truncated"]`` when episode i
ends, plus ``infos[i]["episode"] = {"r", "l", "t"}`` (raw return, length, seconds since
the vector env was made: what SB3's Monitor writes, so PPO logs rollout/ep_rew_mean
without a Monitor wrapper).
"""

from __future__ import annotations

import time
from typing import Any, Dict, List, Optional, Sequence

import numpy as np
from stable_baselines3.common.vec_env.base_vec_env import VecEnv

from .actions import as_action_array
from .arguments import index_argument, seed_argument
from .spaces import box
from .vector import RenderSettings, agent_frequency, canonical_id, make_core_vector_env


class UpkieSB3VecEnv(VecEnv):
    """``num_envs`` environments of one id stepped together in C++ (GIL released, on
    ``num_threads`` workers). Environment i is seeded ``seed + i``: by ``seed`` at the first
    reset, and by ``VecEnv.seed(s)`` at the next one.

    ``render_mode="rgb_array"`` makes ``render()`` tile the frames of the first
    ``render_envs`` environments (all by default), as SB3's ``VecVideoRecorder`` records
    them; ``render_width``, ``render_height`` and ``render_overlay`` as for ``make_vec``."""

    def __init__(
        self,
        env_id: str,
        num_envs: int,
        num_threads: Optional[int] = None,
        seed: Optional[int] = None,
        render_mode: Optional[str] = None,
        render_width: int = 640,
        render_height: int = 480,
        render_envs: Optional[int] = None,
        render_overlay: bool = False,
        **options: Any,
    ) -> None:
        env_id = canonical_id(env_id)
        self.env_id = env_id
        self._render = RenderSettings(
            env_id, render_mode, render_width, render_height, render_envs, render_overlay
        )
        self._core = make_core_vector_env(env_id, num_envs, num_threads, "same_step", options)
        self.render_mode = render_mode
        super().__init__(
            num_envs, box(self._core.observation_space), box(self._core.action_space)
        )
        self.metadata: Dict[str, Any] = {
            **self.metadata, "render_fps": agent_frequency(env_id, options)
        }
        self.num_threads = self._core.num_threads
        self._first_seed = seed_argument(0 if seed is None else seed)
        self._was_reset = False
        self._actions: Optional[np.ndarray] = None
        self._start_time = time.monotonic()
        self._action_shape = (num_envs, len(self._core.action_space[0]))

    def reset(self):
        seed = seed_argument(self._seeds[0])  # VecEnv.seed(s) sets s + i for env i
        if seed is None and not self._was_reset:
            seed = self._first_seed
        self._was_reset = True
        observations = self._core.reset(seed)
        self._reset_seeds()
        self._reset_options()
        return observations

    def step_async(self, actions: np.ndarray) -> None:
        self._actions = as_action_array(actions, self._action_shape, "actions")

    def step_wait(self):
        if self._actions is None:
            raise RuntimeError("step_wait() without step_async()")
        observations, rewards, terminated, truncated = self._core.step(self._actions)
        self._actions = None
        dones = terminated | truncated
        infos: List[dict] = [{} for _ in range(self.num_envs)]
        if dones.any():
            final_observations, returns, lengths = self._core.final_observations()
            elapsed = round(time.monotonic() - self._start_time, 6)
            for i in np.flatnonzero(dones):
                infos[i] = {
                    "terminal_observation": final_observations[i],
                    "TimeLimit.truncated": bool(truncated[i] and not terminated[i]),
                    "episode": {"r": float(returns[i]), "l": int(lengths[i]), "t": elapsed},
                }
        return observations, rewards, dones, infos

    def close(self) -> None:
        self._core = None  # type: ignore[assignment]  # any later use fails

    def get_images(self) -> Sequence[Optional[np.ndarray]]:
        """Frames of the first ``render_envs`` environments (SB3 tiles them in render())."""
        if self.render_mode != "rgb_array":
            return [None for _ in range(self.num_envs)]
        return self._render.frames(self._core, self.num_envs)

    def get_attr(self, attr_name: str, indices=None) -> List[Any]:
        value = getattr(self, attr_name)
        return [value for _ in self._get_indices(indices)]

    def set_attr(self, attr_name: str, value: Any, indices=None) -> None:
        setattr(self, attr_name, value)

    def env_method(self, method_name: str, *method_args, indices=None, **method_kwargs):
        if method_name == "spine_observation":
            return [
                self._core.spine_observation(index_argument(i, self.num_envs))
                for i in self._get_indices(indices)
            ]
        raise AttributeError(f"{self.env_id}: no environment method {method_name!r}")

    def env_is_wrapped(self, wrapper_class, indices=None) -> List[bool]:
        return [False for _ in self._get_indices(indices)]


def make_sb3_vec_env(
    env_id: str,
    num_envs: int,
    num_threads: Optional[int] = None,
    seed: Optional[int] = None,
    **options: Any,
) -> UpkieSB3VecEnv:
    """``num_envs`` environments of ``env_id`` as an SB3 VecEnv stepped in C++."""
    return UpkieSB3VecEnv(env_id, num_envs, num_threads, seed, **options)
