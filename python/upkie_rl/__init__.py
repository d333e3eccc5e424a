"""upkie-rl: Upkie environments simulated in C++, as Gymnasium and SB3 environments.

Importing the package registers every id of ``upkie_rl.registered_env_ids()`` as
``upkie_rl/<id>``, and those of backends the public upkie package lacks (Bullet, MuJoCo)
without the namespace too.

Examples:
    >>> import gymnasium as gym
    >>> import upkie_rl
    >>> env = gym.make("Upkie-Bullet-Pendulum", frequency=200.0)
    >>> venv = upkie_rl.make_vec("Upkie-Bullet-Pendulum", num_envs=10, num_threads=2, seed=0)
    >>> sb3_venv = upkie_rl.make_sb3_vec_env("Upkie-Bullet-Pendulum", num_envs=10, seed=0)
    >>> policy = upkie_rl.load_policy(path)  # a model_*.ckpt or model_*.pt of upkie-rl train
    >>> actions, _ = policy.predict(observations)  # as SB3's model.predict
"""

import os as _os
from pathlib import Path as _Path
from typing import TYPE_CHECKING, Any, Dict, List, Optional

if TYPE_CHECKING:
    from .sb3 import UpkieSB3VecEnv

# An installed package carries the robot model; a build tree's module knows the source's.
_PACKAGED_MODEL = _Path(__file__).parent / "models" / "upkie" / "upkie.urdf"
if _PACKAGED_MODEL.exists():
    _os.environ.setdefault("UPKIE_RL_MODEL", str(_PACKAGED_MODEL))



def _load_mujoco_library():
    """Loads libmujoco.so from the `mujoco` wheel, wherever it is installed, before the
    extension module that links it: the dynamic linker then finds it by its soname."""
    import ctypes
    import importlib.util

    spec = importlib.util.find_spec("mujoco")
    for directory in (spec.submodule_search_locations or []) if spec else []:
        for library in sorted(_Path(directory).glob("libmujoco.so*")):
            ctypes.CDLL(str(library), mode=ctypes.RTLD_GLOBAL)
            return


_load_mujoco_library()

from . import _core  # noqa: E402
from ._core import (  # noqa: E402
    CheckpointError,
    Error,
    InvalidCommandError,
    ModelError,
    OnnxError,
    PolicyOutputError,
    RenderError,
    SimulationDivergedError,
    SpineError,
    SpineTimeoutError,
)
from .env import UpkieEnv  # noqa: E402
from .policy import (  # noqa: E402
    PT_CKPT_TOLERANCE,
    Policy,
    evaluate,
    evaluation_start_options,
    load_policy,
)
from .registration import register  # noqa: E402
from .vector import UpkieVectorEnv, make_vec  # noqa: E402

__version__ = "0.1.0"


def registered_env_ids() -> List[str]:
    """The registry's ids (as the CLI's `upkie-rl envs` lists them)."""
    return _core.registered_env_ids()


def env_options(env_id: str) -> List[Dict[str, Any]]:
    """The options ``env_id`` accepts: name, type, help, default, bounds, choices."""
    from .vector import canonical_id

    return _core.env_options(canonical_id(env_id))


def make_sb3_vec_env(
    env_id: str,
    num_envs: int,
    num_threads: Optional[int] = None,
    seed: Optional[int] = None,
    **options: Any,
) -> "UpkieSB3VecEnv":
    """``num_envs`` environments as a Stable-Baselines3 VecEnv (imports stable_baselines3)."""
    from .sb3 import make_sb3_vec_env as make

    return make(env_id, num_envs, num_threads, seed, **options)


def export_onnx(model, path):
    """Writes the model or checkpoint ``model`` as an ONNX policy at ``path``: raw float32
    observations (batch, obs_dim) in, clipped deterministic actions out, with the
    normalisation inside; metadata: env_id, env_options, spaces, frequency, provenance."""
    _core.export_onnx(str(model), str(path))


def model_provenance(model):
    """How the model or checkpoint ``model`` was made (a dict: upkie-rl version and commit,
    date, source, env id and options, seed, timesteps, training config; "unknown" where an
    older file does not say)."""
    import json

    header, _ = _core.read_model_checkpoint(str(model))
    return json.loads(_core.model_provenance(header))


register()

__all__ = [
    "CheckpointError",
    "Error",
    "InvalidCommandError",
    "ModelError",
    "OnnxError",
    "PolicyOutputError",
    "PT_CKPT_TOLERANCE",
    "Policy",
    "RenderError",
    "SimulationDivergedError",
    "SpineError",
    "SpineTimeoutError",
    "UpkieEnv",
    "UpkieVectorEnv",
    "env_options",
    "evaluate",
    "evaluation_start_options",
    "export_onnx",
    "load_policy",
    "make_sb3_vec_env",
    "make_vec",
    "model_provenance",
    "register",
    "registered_env_ids",
]
