"""The docs say what the code does: every environment id they name exists, the id list of
docs/environments.md is the registry's (read from the registry, so a new id fails this test
until the docs list it), and the Python examples of README.md and docs/python.md run as
written (in a scratch directory, after a tiny training run writes runs/pendulum)."""

import itertools
import os
import re
import subprocess
import sys
from pathlib import Path

import gymnasium as gym
import pytest

import upkie_rl
from upkie_rl.registration import gym_ids as gym_ids_of
from spine_process import cli_path

ROOT = Path(__file__).resolve().parents[2]
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
ID_LIST_START = "<!-- registry ids"
ID_LIST_END = "<!-- end of registry ids -->"
# Aliases the registry accepts besides its canonical ids.
ALIAS_BACKENDS = {"PyBullet": "Bullet"}
# Ids of the public upkie package that the docs compare with (never registered by us).
PUBLIC_UPKIE_TASKS = {"BaseVelocity"}
# Mistyped on purpose: the error examples (README "Commands", docs/reliability.md).
ERROR_EXAMPLES = {"Upkie-Bullet-Pendlum", "Upkie-Mujoco-Pendulum"}


def expand(pattern: str):
    """Upkie-{A,B}-{C,D} -> the four ids."""
    parts = re.split(r"(\{[^}]*\})", pattern)
    choices = [part[1:-1].split(",") if part.startswith("{") else [part] for part in parts]
    return ["".join(combination) for combination in itertools.product(*choices)]


def named_ids(text: str):
    """Every id a text names, brace patterns expanded; patterns with * are left out."""
    ids = set()
    for match in re.finditer(r"Upkie-(?:\{[A-Za-z,]+\}|[A-Za-z]+)-(?:\{[A-Za-z,]+\}|[A-Za-z]+)",
                             text):
        ids.update(expand(match.group(0)))
    return ids


def test_every_id_the_docs_name_is_registered():
    registered = set(upkie_rl.registered_env_ids())
    for path in DOCS:
        for env_id in sorted(named_ids(path.read_text())):
            _, backend, task = env_id.split("-")
            canonical = f"Upkie-{ALIAS_BACKENDS.get(backend, backend)}-{task}"
            if task in PUBLIC_UPKIE_TASKS or env_id in ERROR_EXAMPLES:
                continue
            assert canonical in registered, f"{path.name} names {env_id}, not a registered id"


def test_the_id_list_of_the_docs_is_the_registry():
    text = (ROOT / "docs" / "environments.md").read_text()
    start = text.index(ID_LIST_START)
    block = text[start:text.index(ID_LIST_END, start)]
    rows = re.findall(r"^\| `(Upkie-[A-Za-z]+-[A-Za-z]+)` \| (.*) \| (\w+) \|$", block,
                      flags=re.MULTILINE)
    listed = [env_id for env_id, _, _ in rows]
    assert len(listed) == len(set(listed)), "an id is listed twice"
    registered = upkie_rl.registered_env_ids()
    assert sorted(listed) == sorted(registered), (
        "docs/environments.md's id list differs from the registry: "
        f"missing {sorted(set(registered) - set(listed))}, "
        f"not registered {sorted(set(listed) - set(registered))}")
    for env_id, gym_ids, limit in rows:
        assert re.findall(r"`([^`]+)`", gym_ids) == gym_ids_of(env_id), env_id
        assert gym.spec(f"upkie_rl/{env_id}").max_episode_steps == (
            None if limit == "none" else int(limit)), env_id


def python_blocks(path: Path):
    return re.findall(r"```python\n(.*?)```", path.read_text(), flags=re.DOTALL)


@pytest.mark.needs_torch_numpy  # conftest.py: the examples load a TorchScript policy
@pytest.mark.parametrize("doc", ["README.md", "docs/python.md"])
def test_python_examples_run_as_written(doc, tmp_path):
    """The examples of one file run in order, in one interpreter, from a scratch directory
    holding a tiny training run in runs/pendulum (what `upkie-rl train --config
    configs/pendulum.yaml --run-dir runs/pendulum` writes)."""
    pytest.importorskip("stable_baselines3")
    blocks = python_blocks(ROOT / doc)
    assert blocks, f"{doc} has no Python example"
    subprocess.run(
        [str(cli_path()), "train", "--config", str(ROOT / "configs" / "pendulum.yaml"),
         "--run-dir", str(tmp_path / "runs" / "pendulum"), "--set", "ppo.total_timesteps=2048",
         "--set", "checkpoint_every=2048", "--quiet"],
        check=True, capture_output=True)
    script = tmp_path / "examples.py"
    script.write_text("\n".join(blocks))
    result = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                            text=True, env=dict(os.environ), timeout=300)
    assert result.returncode == 0, f"{doc}'s examples fail:\n{result.stderr[-3000:]}"
