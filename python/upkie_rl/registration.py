"""Gymnasium ids of every environment of the C++ registry.

Every id is registered in the ``upkie_rl`` namespace (``upkie_rl/Upkie-Mock-Pendulum``), so
that ours never replace the public ``upkie`` package's ``Upkie-{Mock,PyBullet,Spine}-*``
when both are imported. Ids of backends the public package does not have (Bullet) are also
registered without the namespace, so ``gym.make("Upkie-Bullet-Pendulum")`` works as the
CLI's id does.
"""

from __future__ import annotations

import gymnasium as gym

from . import _core

NAMESPACE = "upkie_rl"
#: Backends the public upkie package also registers, whose bare ids are left to it.
PUBLIC_BACKENDS = ("Mock", "PyBullet", "Spine")


def max_episode_steps(env_id: str):
    """The id's default time limit (None for none)."""
    for option in _core.env_options(env_id):
        if option["name"] == "max_episode_steps":
            steps = int(option["default"])
            return steps if steps > 0 else None
    return None


def gym_ids(env_id: str):
    """The Gymnasium ids under which ``env_id`` is registered."""
    ids = [f"{NAMESPACE}/{env_id}"]
    backend = env_id.split("-")[1]
    if backend not in PUBLIC_BACKENDS:
        ids.append(env_id)
    return ids


def register() -> None:
    """Registers every id (idempotent)."""
    for env_id in _core.registered_env_ids():
        for gym_id in gym_ids(env_id):
            if gym_id in gym.registry:
                continue
            gym.register(
                id=gym_id,
                entry_point="upkie_rl.env:UpkieEnv",
                vector_entry_point="upkie_rl.vector:make_vec",
                max_episode_steps=max_episode_steps(env_id),
                kwargs={"env_id": env_id},
            )
