"""Trained policies of ``upkie-rl train`` in Python: deterministic actions for raw
observations, for evaluation and deployment.

``load_policy(path)`` reads either file the trainer writes:

- ``model_*.ckpt`` (or a checkpoint): evaluated by the C++ extension, without torch;
- ``model_*.pt``: the TorchScript export, evaluated by torch (``torch.jit.load``).

Both apply the frozen observation normalisation saved with the model, run the actor and
clip its mean to the action bounds. They compute in different float32 operation orders, so
their actions agree to ``PT_CKPT_TOLERANCE`` (absolute, per component), not bit for bit.
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path
from typing import Any, List, Optional, Tuple, Union

import gymnasium as gym
import numpy as np

from . import _core
from .arguments import flag_argument, integer_argument
from .spaces import box
from .vector import canonical_id

# The TorchScript metadata names its entries after the checkpoint header's and the
# provenance's keys (rl/runs/torchscript_export.cpp), read from their one declaration.
_HEADER_KEY = _core.checkpoint_header_keys()
_PROVENANCE_KEY = _core.provenance_keys()

#: Largest difference between the actions of a ``.pt`` export and its ``.ckpt`` (absolute,
#: per component), measured on trained pendulum policies (python/tests/test_policy.py).
PT_CKPT_TOLERANCE = 1e-5


class Policy:
    """A loaded policy: ``policy(observation)`` maps a raw float32 observation of shape
    (obs_dim,) or a batch (n, obs_dim) to the action(s) (act_dim,) or (n, act_dim)."""

    env_id: str
    observation_space: gym.spaces.Box
    action_space: gym.spaces.Box

    def __call__(self, observation) -> np.ndarray:
        observation = np.asarray(observation)
        if observation.dtype.kind not in "fiu":
            raise TypeError(f"observation must be real numbers, got dtype {observation.dtype}")
        size = self.observation_space.shape[0]
        if observation.shape[-1:] != (size,) or observation.ndim > 2:
            raise ValueError(
                f"observation has shape {observation.shape}, expected ({size},) or (n, {size})"
            )
        return self._act(np.ascontiguousarray(observation, dtype=np.float32))

    def predict(
        self,
        observation: Any,
        state: Optional[Tuple[np.ndarray, ...]] = None,
        episode_start: Optional[np.ndarray] = None,
        deterministic: bool = True,
    ) -> Tuple[np.ndarray, Optional[Tuple[np.ndarray, ...]]]:
        """Stable-Baselines3's ``model.predict``: the action(s) for one observation (obs_dim,)
        or a batch (n, obs_dim), and the recurrent ``state``, passed through (these
        policies have none). ``episode_start`` is accepted and unused, like SB3's
        feed-forward policies. Only deterministic actions exist in an exported policy (the
        actor's mean): ``deterministic=False`` raises ValueError."""
        if not deterministic:
            raise ValueError(
                "an upkie-rl policy file holds the actor's mean only: predict() gives "
                "deterministic actions (deterministic=True)"
            )
        return self(observation), state

    def check_env(self, env) -> None:
        """Raises ValueError unless ``env``'s flat spaces are the policy's."""
        for what in ("observation_space", "action_space"):
            mine, theirs = getattr(self, what), getattr(env, what)
            if (
                not isinstance(theirs, gym.spaces.Box)
                or mine.shape != theirs.shape
                or not np.array_equal(mine.low, theirs.low)
                or not np.array_equal(mine.high, theirs.high)
            ):
                raise ValueError(
                    f"the policy's {what} {mine} differs from the environment's {theirs}"
                )

    def _act(self, observation: np.ndarray) -> np.ndarray:
        raise NotImplementedError


class CheckpointPolicy(Policy):
    """A ``.ckpt`` model evaluated by the C++ extension (no torch)."""

    def __init__(self, path: Union[str, Path]):
        self._core = _core.Policy(str(path))
        self.env_id = self._core.env_id
        self.observation_space = box(self._core.observation_space)
        self.action_space = box(self._core.action_space)

    def _act(self, observation: np.ndarray) -> np.ndarray:
        if observation.ndim == 1:
            return self._core.act(observation)
        return self._core.act_batch(observation)


class TorchScriptPolicy(Policy):
    """A ``.pt`` TorchScript export evaluated by torch."""

    def __init__(self, path: Union[str, Path]):
        import torch

        extra_files = {"metadata.json": ""}
        try:
            self._module = torch.jit.load(str(path), _extra_files=extra_files)
            metadata = json.loads(extra_files["metadata.json"])
            spaces = {
                what: (
                    np.array(metadata[what]["low"], dtype=np.float32),
                    np.array(metadata[what]["high"], dtype=np.float32),
                    metadata[what].get("names", []),
                )
                for what in (_HEADER_KEY["OBSERVATION_SPACE"], _HEADER_KEY["ACTION_SPACE"])
            }
        except (RuntimeError, ValueError, KeyError) as error:
            raise ValueError(f"{path}: not an upkie-rl TorchScript policy ({error})") from error
        self._torch = torch
        self.env_id = metadata[_PROVENANCE_KEY["ENV_ID"]]
        self.observation_space = box(spaces[_HEADER_KEY["OBSERVATION_SPACE"]])
        self.action_space = box(spaces[_HEADER_KEY["ACTION_SPACE"]])

    def _act(self, observation: np.ndarray) -> np.ndarray:
        with self._torch.no_grad():
            return self._module(self._torch.from_numpy(observation)).numpy()


#: Episode seeds wrap around past the largest seed, as the C++ side's 64-bit ones do.
_SEED_MODULUS = _core.ARGUMENT_RANGES["seed"][1] + 1


def load_policy(path: Union[str, Path]) -> Policy:
    """Loads ``model_*.ckpt`` (C++, no torch) or ``model_*.pt`` (TorchScript, needs torch).

    Raises FileNotFoundError for a missing file and ValueError naming the file and the
    problem for a damaged or foreign one."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"no policy file {path}")
    if path.suffix == ".pt":
        return TorchScriptPolicy(path)
    return CheckpointPolicy(path)


def evaluate(
    policy: Policy,
    env_id: str,
    episodes: int = 10,
    seed: int = 0,
    exact_start: bool = False,
    **options: Any,
) -> List[Tuple[float, int]]:
    """Rolls out ``policy`` deterministically on ``env_id`` (a fresh environment, episode k
    seeded ``seed + k``); returns the list of (return, length) per episode.

    Episodes start from the evaluation's random initial state (``evaluation_start_options``:
    each initial-state randomisation the id has, left at zero by its defaults and not given
    in ``options``, gets the evaluation's bound), so that N episodes are N different ones.
    ``exact_start=True`` keeps the environment's own start (the pendulum's is the same
    every episode, as in upkie's environments). Warns (UserWarning) when every episode
    was the same.

    ``episodes`` is in [1, 1000000] (as ``upkie-rl evaluate --episodes``), ``seed`` in
    [0, 2**64 - 1] (seeds past it wrap around, as the command line's); TypeError or
    ValueError otherwise, naming the argument."""
    episodes = integer_argument("episodes", episodes)
    seed = integer_argument("seed", seed)
    env_id = canonical_id(env_id)
    if not flag_argument("exact_start", exact_start):
        options = evaluation_start_options(env_id, options)
    # Always our id: a bare Upkie-Mock-* or Upkie-Spine-* may be the public upkie package's.
    env = gym.make(f"upkie_rl/{env_id}", **options)
    policy.check_env(env)
    results = []
    for episode in range(episodes):
        observation, _ = env.reset(seed=(seed + episode) % _SEED_MODULUS)
        total, length, done = 0.0, 0, False
        while not done:
            observation, reward, terminated, truncated, _ = env.step(policy(observation))
            total += float(reward)
            length += 1
            done = terminated or truncated
        results.append((total, length))
    env.close()
    warning = _core.identical_episodes_warning([r for r, _ in results], [n for _, n in results])
    if warning:
        warnings.warn(warning, UserWarning, stacklevel=2)
    return results


def evaluation_start_options(env_id: str, options: Optional[dict] = None) -> dict:
    """``options`` with the evaluations' initial-state randomisation added: what
    ``evaluate`` (and the CLI's ``rollout`` and ``evaluate``) use unless asked for the exact
    start."""
    options = dict(options or {})
    for name, value in _core.evaluation_start_options(canonical_id(env_id), list(options)):
        options[name] = float(value)
    return options
