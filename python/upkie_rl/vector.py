"""UpkieVectorEnv: n C++ environments as one ``gymnasium.vector.VectorEnv``, and make_vec."""

from __future__ import annotations

import os
from typing import Any, List, Optional, Tuple

import gymnasium as gym
import numpy as np
from gymnasium.vector.utils import batch_space

from . import _core
from .actions import as_action_array
from .arguments import (
    env_id_argument,
    flag_argument,
    index_argument,
    integer_argument,
    render_size,
    seed_argument,
)
from .options import to_env_options
from .spaces import box, is_nested

#: Gymnasium's autoreset mode names, and the C++ side's name of each.
AUTORESET_MODES = {"NextStep": "next_step", "SameStep": "same_step"}


def autoreset_mode_name(mode: Any) -> str:
    """"NextStep" or "SameStep" of a mode given as ``gymnasium.vector.AutoresetMode`` (1.1+)
    or as its name; ValueError for anything else (``Disabled`` included)."""
    name = getattr(mode, "value", mode)
    if name not in AUTORESET_MODES:
        raise ValueError(f"autoreset_mode {mode!r}: expected one of {list(AUTORESET_MODES)}")
    return str(name)


def autoreset_mode_metadata(name: str) -> Any:
    """What ``metadata["autoreset_mode"]`` holds: Gymnasium's ``AutoresetMode`` enum where it
    exists (1.1+; its vector wrappers require the enum), the name in Gymnasium 1.0."""
    enum = getattr(gym.vector, "AutoresetMode", None)
    return name if enum is None else enum(name)


def default_num_threads(num_envs: int) -> int:
    """One worker per core, at most one per environment; 0 (the calling thread) for one env."""
    if num_envs <= 1:
        return 0
    return min(num_envs, len(os.sched_getaffinity(0)))


def make_core_vector_env(
    env_id: str, num_envs: int, num_threads: Optional[int], autoreset: str, options: dict
) -> "_core.VectorEnv":
    """The C++ vector env behind both Python vector classes. Raises TypeError or ValueError
    on a bad count (arguments.py), and ValueError for the Servos ids, whose nested dicts the
    flat batch cannot carry."""
    num_envs = integer_argument("num_envs", num_envs)
    if num_threads is None:
        num_threads = default_num_threads(num_envs)
    num_threads = integer_argument("num_threads", num_threads)
    if is_nested(env_id):
        raise ValueError(
            f"{env_id}: vector envs step flat arrays; use the ServosTask id, or "
            "gym.make_vec(..., vectorization_mode='sync') for nested servo dicts"
        )
    return _core.VectorEnv(
        env_id, to_env_options(env_id, options), num_envs, num_threads, autoreset
    )


class UpkieVectorEnv(gym.vector.VectorEnv):
    """n environments of one id stepped together in C++: one ``step`` call steps them all
    with the GIL released, on ``num_threads`` workers (0: the calling thread).

    Autoreset (``metadata["autoreset_mode"]``): "NextStep" (Gymnasium's default) or
    "SameStep" (the last observation of an ended episode in ``infos["final_obs"]``, with the
    mask ``infos["_final_obs"]``; its raw return and length in ``infos["final_info"]``).

    Environment i is seeded ``seed + i`` at the first reset (``seed`` of the constructor,
    0 if none) and at every ``reset(seed=...)``; ``reset()`` without a seed lets each
    environment's generator continue. Results are identical for any ``num_threads``.

    ``spine_observation=True`` adds each environment's full observation dictionary to
    ``infos["spine_observation"]`` (an object array) at every step; it is off by default
    (about 8 us per environment and step, 2% of a Bullet pendulum step).

    Rendering (``render_mode="rgb_array"``): ``render()`` returns a tuple of ``num_envs``
    frames, (``render_height``, ``render_width``, 3) uint8, as Gymnasium's SyncVectorEnv
    does, so its vector ``RecordVideo`` tiles them. ``render_envs=k`` draws only the first k
    (each frame takes about 19 ms at 640 x 480) and gives None for the others (use it with
    ``RecordVideo(..., record_first_only=True)`` and k=1). ``render_overlay=True`` writes
    the time and pitch on the frames.
    """

    def __init__(
        self,
        env_id: str,
        num_envs: int,
        num_threads: Optional[int] = None,
        seed: Optional[int] = None,
        autoreset_mode: Any = "NextStep",
        spine_observation: bool = False,
        render_mode: Optional[str] = None,
        render_width: int = 640,
        render_height: int = 480,
        render_envs: Optional[int] = None,
        render_overlay: bool = False,
        **options: Any,
    ) -> None:
        mode = autoreset_mode_name(autoreset_mode)
        self.env_id = env_id = canonical_id(env_id)
        self._render = RenderSettings(
            env_id, render_mode, render_width, render_height, render_envs, render_overlay
        )
        self._core = make_core_vector_env(
            env_id, num_envs, num_threads, AUTORESET_MODES[mode], options
        )
        self.num_envs = num_envs
        self.num_threads = self._core.num_threads
        self.metadata = {
            "autoreset_mode": autoreset_mode_metadata(mode),
            "render_modes": ["rgb_array"],
            "render_fps": agent_frequency(env_id, options),
        }
        self.render_mode = render_mode
        self.single_observation_space = box(self._core.observation_space)
        self.single_action_space = box(self._core.action_space)
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)
        self._action_shape = (num_envs, self.single_action_space.shape[0])
        self._seed = seed_argument(0 if seed is None else seed)
        self._was_reset = False
        self._same_step = mode == "SameStep"
        self._spine_observation = flag_argument("spine_observation", spine_observation)

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        if options:
            raise ValueError(f"{self.env_id}: reset options are not supported")
        seed = seed_argument(seed)
        if seed is not None:
            self._np_random, self._np_random_seed = gym.utils.seeding.np_random(seed)
        elif not self._was_reset:
            seed = self._seed
        self._was_reset = True
        observations = self._core.reset(seed)
        infos: dict = {}
        if self._spine_observation:
            self._add_spine_observations(infos)
        return observations, infos

    def step(self, actions):
        actions = as_action_array(actions, self._action_shape, "actions")
        observations, rewards, terminated, truncated = self._core.step(actions)
        infos: dict = {}
        ended = terminated | truncated
        if self._same_step and ended.any():
            final_observations, returns, lengths = self._core.final_observations()
            final_obs = np.empty(self.num_envs, dtype=object)
            final_info = np.empty(self.num_envs, dtype=object)
            for i in np.flatnonzero(ended):
                final_obs[i] = final_observations[i]
                final_info[i] = {"episode": {"r": float(returns[i]), "l": int(lengths[i])}}
            infos.update(
                final_obs=final_obs, _final_obs=ended, final_info=final_info, _final_info=ended
            )
        if self._spine_observation:
            self._add_spine_observations(infos)
        return observations, rewards.astype(np.float64), terminated, truncated, infos

    def render(self) -> Optional[Tuple[Any, ...]]:  # frames, None past render_envs
        """One frame per environment (None past ``render_envs``); None without a
        render_mode."""
        if self.render_mode is None:
            gym.logger.warn(
                f"{self.env_id}: render() without a render_mode; make the vector env with "
                "render_mode='rgb_array'"
            )
            return None
        frames = self._render.frames(self._core, self.num_envs)
        return tuple(frames + [None] * (self.num_envs - len(frames)))

    def spine_observation(self, index: int) -> Optional[dict]:
        """Environment ``index``'s full observation dictionary after the last step."""
        return self._core.spine_observation(index_argument(index, self.num_envs))

    def close_extras(self, **kwargs: Any) -> None:
        self._core = None  # type: ignore[assignment]  # any later use fails

    def _add_spine_observations(self, infos: dict) -> None:
        observations = np.empty(self.num_envs, dtype=object)
        for i in range(self.num_envs):
            observations[i] = self._core.spine_observation(i)
        infos["spine_observation"] = observations
        infos["_spine_observation"] = np.ones(self.num_envs, dtype=bool)


class RenderSettings:
    """The frames a vector env draws: their size, how many environments, with or without the
    caption. Checks the settings where they are given."""

    def __init__(
        self,
        env_id: str,
        render_mode: Optional[str],
        width: int,
        height: int,
        count: Optional[int],
        overlay: bool,
    ) -> None:
        if render_mode not in (None, "rgb_array"):
            raise ValueError(
                f"{env_id}: render_mode {render_mode!r} is not supported; use 'rgb_array'"
            )
        self.size = render_size(width, height)
        self.count = None if count is None else integer_argument("render_envs", count)
        self.overlay = flag_argument("render_overlay", overlay)

    def frames(self, core: Any, num_envs: int) -> List[np.ndarray]:
        """Frames of the first ``count`` environments (all without a count)."""
        count = num_envs if self.count is None else min(self.count, num_envs)
        return [core.render(i, *self.size, self.overlay) for i in range(count)]


def agent_frequency(env_id: str, options: dict) -> float:
    """Steps per second of ``env_id``'s environments with ``options`` (its ``frequency``
    option): the real-time frame rate of their videos."""
    if "frequency" in options:
        return float(options["frequency"])
    for option in _core.env_options(env_id):
        if option["name"] == "frequency":
            return float(option["default"])
    raise ValueError(f"{env_id}: no frequency option")


def make_vec(
    env_id: str,
    num_envs: int = 1,
    num_threads: Optional[int] = None,
    seed: Optional[int] = None,
    **options: Any,
) -> UpkieVectorEnv:
    """``num_envs`` environments of ``env_id`` as a Gymnasium vector env stepped in C++.

    Also the ids' ``vector_entry_point``: ``gym.make_vec(id, n,
    vectorization_mode="vector_entry_point", **kwargs)`` comes here. Ids may carry the
    ``upkie_rl/`` namespace. Keyword arguments: ``autoreset_mode`` (``AutoresetMode``
    NEXT_STEP or SAME_STEP, or their names "NextStep", "SameStep"), ``spine_observation``
    (bool), ``render_mode`` ("rgb_array"), ``render_width``, ``render_height``,
    ``render_envs``, ``render_overlay``, and the registry's options.
    """
    return UpkieVectorEnv(env_id, num_envs, num_threads, seed, **options)


def canonical_id(env_id: str) -> str:
    """The registry's id of a Gymnasium id (without the ``upkie_rl/`` namespace); TypeError
    for an id that is not a string."""
    env_id = env_id_argument(env_id)
    prefix = "upkie_rl/"
    return env_id[len(prefix) :] if env_id.startswith(prefix) else env_id
