"""What a user's script looks like to mypy (`make typecheck-python` checks this file with the
package's py.typed and stubs): every call below is typed, none is Any by accident."""

from typing import List, Optional, Tuple

import numpy as np
import numpy.typing as npt

import upkie_rl


def first_actions(model_path: str) -> Tuple[np.ndarray, Optional[Tuple[np.ndarray, ...]]]:
    policy: upkie_rl.Policy = upkie_rl.load_policy(model_path)
    observations: npt.NDArray[np.float32] = np.zeros((3, 4), dtype=np.float32)
    return policy.predict(observations, deterministic=True)


def evaluation(model_path: str) -> List[Tuple[float, int]]:
    return upkie_rl.evaluate(upkie_rl.load_policy(model_path), "Upkie-Bullet-Pendulum", 3)


def frames(num_envs: int) -> int:
    venv = upkie_rl.make_vec("Upkie-MuJoCo-Pendulum", num_envs, render_mode="rgb_array")
    venv.reset(seed=0)
    rendered = venv.render()
    return 0 if rendered is None else sum(frame is not None for frame in rendered)


def ids() -> List[str]:
    return upkie_rl.registered_env_ids()
