"""Gymnasium spaces of the C++ Box spaces, and the nested-dict view of the Servos ones.

A C++ space is (low, high, names). The Servos environment's components, named ``joint.key``,
form upkie's nested Dict spaces: one Dict per joint, one shape-(1,) float32 Box per key.
"""

from __future__ import annotations

from typing import Dict, List, Tuple

import gymnasium as gym
import numpy as np


def box(space: Tuple[np.ndarray, np.ndarray, List[str]]) -> gym.spaces.Box:
    low, high, _ = space
    return gym.spaces.Box(low=low, high=high, dtype=np.float32)


def is_nested(env_id: str) -> bool:
    """True for the Servos environments, whose actions and observations are upkie's nested
    dicts (their components are named ``joint.key``)."""
    return env_id.endswith("-Servos")


class NestedLayout:
    """Where each ``joint.key`` component of a flat vector lives, and the Dict space."""

    def __init__(self, space: Tuple[np.ndarray, np.ndarray, List[str]]):
        low, high, names = space
        self.index: Dict[str, Dict[str, int]] = {}
        for i, name in enumerate(names):
            joint, key = name.split(".")
            self.index.setdefault(joint, {})[key] = i
        self.size = len(names)
        self.space = gym.spaces.Dict(
            {
                joint: gym.spaces.Dict(
                    {
                        key: gym.spaces.Box(
                            low=low[i], high=high[i], shape=(1,), dtype=np.float32
                        )
                        for key, i in keys.items()
                    }
                )
                for joint, keys in self.index.items()
            }
        )

    def to_nested(self, flat: np.ndarray) -> Dict[str, Dict[str, np.ndarray]]:
        """upkie's observation dict: {joint: {key: float32 array of shape (1,)}}."""
        return {
            joint: {key: flat[i : i + 1].copy() for key, i in keys.items()}
            for joint, keys in self.index.items()
        }

    def to_flat(self, nested, neutral: np.ndarray) -> np.ndarray:
        """A flat float32 action from upkie's nested action dict; missing joints and keys
        take their neutral value. Raises KeyError naming an unknown joint or key and
        ValueError on a value that is not one real number."""
        if not isinstance(nested, dict):
            raise TypeError(
                f"action must be a dict {{joint: {{key: value}}}}, got {type(nested).__name__}"
            )
        flat = neutral.copy()
        for joint, commands in nested.items():
            if joint not in self.index:
                raise KeyError(f"unknown joint {joint!r} in action; joints: {list(self.index)}")
            keys = self.index[joint]
            for key, value in commands.items():
                if key not in keys:
                    raise KeyError(f"unknown key {joint}.{key} in action; keys: {list(keys)}")
                array = np.asarray(value)
                if array.size != 1 or array.dtype.kind not in "fiub":
                    raise ValueError(f"action {joint}.{key} must be one real number, got {value!r}")
                flat[keys[key]] = array.reshape(-1)[0]
        return flat
