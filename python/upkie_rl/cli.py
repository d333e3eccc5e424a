"""The ``upkie-rl`` command of the Python wheel.

The command-line tool (``upkie-rl train``, ``rollout``, ``evaluate``, ...) is the C++ program
of the source build: it trains with libtorch, which the wheel does not carry. This entry
point runs that program when another ``upkie-rl`` is on PATH (a source build installed there),
and otherwise says so and how to train from Python instead, with exit status 2.
"""

import os
import shutil
import sys
from pathlib import Path
from typing import List, Optional

MESSAGE = """\
upkie-rl: the command-line tool (train, rollout, evaluate, ...) is not in the Python wheel.
It is the C++ program of the source build, which links libtorch to train; build it with
`make build` in a clone of the repository (docs/install.md), then run build/upkie-rl.

From this Python package, train with Stable-Baselines3 instead:
    pip install "stable-baselines3>=2.4" pyyaml
    python3 -c "import upkie_rl, stable_baselines3 as sb3; \\
venv = upkie_rl.make_sb3_vec_env('Upkie-Bullet-Pendulum', num_envs=8, seed=0); \\
sb3.PPO('MlpPolicy', venv).learn(100_000).save('ppo.zip')"
and `python3 -m upkie_rl.sb3_convert import ppo.zip --env Upkie-Bullet-Pendulum --output
model.ckpt` makes an upkie-rl model of it (docs/python.md, "Training from the wheel")."""


def _source_build_tool() -> Optional[str]:
    """Another ``upkie-rl`` on PATH than this script, or None."""
    this = Path(sys.argv[0]).resolve() if sys.argv and sys.argv[0] else None
    for directory in os.environ.get("PATH", "").split(os.pathsep):
        candidate = shutil.which("upkie-rl", path=directory) if directory else None
        if candidate and (this is None or Path(candidate).resolve() != this):
            return candidate
    return None


def main(argv: Optional[List[str]] = None) -> int:
    arguments = sys.argv[1:] if argv is None else argv
    tool = _source_build_tool()
    if tool is not None:
        os.execv(tool, [tool, *arguments])
    print(MESSAGE, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main())
