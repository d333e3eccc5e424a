"""UpkieEnv: one C++ environment of the registry as a ``gymnasium.Env``."""

from __future__ import annotations

from typing import Any, Optional

import gymnasium as gym
import numpy as np

from . import _core
from .actions import as_action_array
from .arguments import env_id_argument, flag_argument, render_size, seed_argument
from .options import to_env_options
from .spaces import NestedLayout, box, is_nested


class UpkieEnv(gym.Env):
    """An upkie-rl environment (``Upkie-{Bullet,Mock,Spine}-{Servos,Pendulum,Gyropod,
    ServosTask,Velocity}``) stepped in C++.

    Observations are float32 arrays (the Servos environment: upkie's nested dicts
    ``{joint: {key: array of shape (1,)}}``); rewards Python floats; ``terminated`` and
    ``truncated`` Python bools; ``info["spine_observation"]`` the full observation dictionary
    with the Upkie spine's keys. Options are the registry's, as keyword arguments
    (``frequency=200.0``, ``fall_pitch=0.8``...; ``upkie-rl envs --options`` lists them).

    Time limits: ``gym.make`` applies the id's ``max_episode_steps`` with Gymnasium's
    TimeLimit, so this class asks the C++ side for none unless ``max_episode_steps`` is
    given to it directly.

    Rendering (``render_mode="rgb_array"``): ``render_width`` x ``render_height`` frames of
    the robot, clean by default; ``render_overlay=True`` writes the time and pitch on them.

    ``spine_observation=False`` leaves ``info`` empty: building the dictionary takes about
    8 us per step (2% of a Bullet pendulum step), which a trainer that never reads it can
    skip.
    """

    metadata = {"render_modes": ["rgb_array"], "render_fps": 0}

    def __init__(
        self,
        env_id: str,
        render_mode: Optional[str] = None,
        spine_observation: bool = True,
        render_width: int = 640,
        render_height: int = 480,
        render_overlay: bool = False,
        **options: Any,
    ) -> None:
        env_id_argument(env_id)  # its messages below quote it
        if render_mode not in (None, "rgb_array"):
            raise ValueError(
                f"{env_id}: render_mode {render_mode!r} is not supported; use 'rgb_array'"
            )
        self._render_size = render_size(render_width, render_height)
        self._render_overlay = flag_argument("render_overlay", render_overlay)
        options.setdefault("max_episode_steps", 0)
        self.env_id = env_id
        self.render_mode = render_mode
        self._with_spine_observation = flag_argument("spine_observation", spine_observation)
        self._core = _core.Env(env_id, to_env_options(env_id, options))
        # Real time: one frame per step (RecordVideo writes videos at this rate).
        self.metadata = {"render_modes": ["rgb_array"], "render_fps": 1.0 / self._core.timestep}
        observation_space = self._core.observation_space
        action_space = self._core.action_space
        nested = is_nested(env_id)
        self._observation_layout = NestedLayout(observation_space) if nested else None
        self._action_layout = NestedLayout(action_space) if nested else None
        self.observation_space = (
            self._observation_layout.space if self._observation_layout else box(observation_space)
        )
        self.action_space = self._action_layout.space if self._action_layout else box(action_space)
        self._action_shape = (len(action_space[2]),)
        self._neutral_action = self._core.neutral_action()

    @property
    def dt(self) -> float:
        """Duration of one step [s]."""
        return self._core.timestep

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        """Starts an episode: a seed re-seeds the environment's generator (initial-state
        randomisation); without one it continues."""
        seed = seed_argument(seed)
        super().reset(seed=seed)
        if options:
            raise ValueError(
                f"{self.env_id}: reset options are not supported (give options to gym.make)"
            )
        observation = self._core.reset(seed)
        return self._observation(observation), self._info()

    def step(self, action):
        if self._action_layout is not None:
            flat = self._action_layout.to_flat(action, self._neutral_action)
        else:
            flat = as_action_array(action, self._action_shape)
        observation, reward, terminated, truncated = self._core.step(flat)
        return self._observation(observation), reward, terminated, truncated, self._info()

    def neutral_action(self):
        """The action that commands nothing (upkie's neutral servo action for Servos)."""
        if self._action_layout is not None:
            return self._action_layout.to_nested(self._neutral_action)
        return self._neutral_action.copy()

    def render(self):
        """With render_mode="rgb_array": the robot drawn offscreen (EGL, no display or
        GPU) from the simulator's ground truth, a (height, width, 3) uint8 array."""
        if self.render_mode is None:
            gym.logger.warn(
                f"{self.env_id}: render() without a render_mode; make the env with "
                "render_mode='rgb_array'"
            )
            return None
        return self._core.render(*self._render_size, self._render_overlay)

    def set_randomization_scale(self, scale: float) -> None:
        """Multiplies every randomisation bound (initial state, perturbations, noise, lag,
        pushes) by ``scale`` in [0, 1] from the next reset on: a curriculum."""
        self._core.set_randomization_scale(float(scale))

    def get_spine_observation(self) -> Optional[dict]:
        """The full observation dictionary of the last reset or step."""
        return self._core.spine_observation()

    def close(self) -> None:
        if hasattr(self, "_core"):
            self._core = _ClosedEnv(self.env_id)  # type: ignore[assignment]  # any use raises

    def _observation(self, flat: np.ndarray):
        if self._observation_layout is not None:
            return self._observation_layout.to_nested(flat)
        return flat

    def _info(self) -> dict:
        if not self._with_spine_observation:
            return {}
        observation = self._core.spine_observation()
        return {} if observation is None else {"spine_observation": observation}


class _ClosedEnv:
    """Stands in for a closed environment's C++ object: any use raises."""

    def __init__(self, env_id: str):
        self._env_id = env_id

    def __getattr__(self, name):
        raise RuntimeError(f"{self._env_id}: the environment is closed")
