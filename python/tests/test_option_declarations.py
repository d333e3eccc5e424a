"""Every environment option is declared once, in C++, beside its settings struct: the
``upkie-rl envs --options`` listing, the typed table behind the keyword arguments of
``gym.make`` and the registry's parser must all come from those declarations (an option
declared on one side only fails here)."""

import os
import re
import subprocess
from pathlib import Path
from typing import Any, Dict, List

import pytest

import upkie_rl
from upkie_rl import _core
from upkie_rl.options import to_env_options


def cli_listing() -> Dict[str, List[str]]:
    """The option names ``upkie-rl envs --options`` lists, by id."""
    cli = Path(os.environ.get("UPKIE_RL_BUILD_DIR", "build")) / "upkie-rl"
    if not cli.exists():
        pytest.skip(f"{cli} is not built")
    text = subprocess.run(
        [str(cli), "envs", "--options"], check=True, capture_output=True, text=True
    ).stdout
    listing: Dict[str, List[str]] = {}
    current = None
    in_options = False
    for line in text.splitlines():
        if re.fullmatch(r"Upkie-\w+-\w+", line):
            current, in_options = line, False
            listing[current] = []
        elif line == "  options:":
            in_options = True
        elif in_options and current is not None and line.startswith("      "):
            listing[current].append(line.strip().split(":", 1)[0])
    return listing


def test_cli_listing_and_python_table_hold_the_same_options():
    listing = cli_listing()
    assert sorted(listing) == sorted(_core.registered_env_ids())
    for env_id, names in listing.items():
        table = [option["name"] for option in _core.env_options(env_id)]
        assert names == table, env_id


@pytest.mark.parametrize("env_id", _core.registered_env_ids())
def test_every_default_goes_through_the_keyword_arguments(env_id):
    """Each option's listed default, typed as Python would give it, is accepted by the
    keyword-argument layer and by the C++ parser."""
    keywords: Dict[str, Any] = {}
    for option in upkie_rl.env_options(env_id):
        default, kind = option["default"], option["type"]
        if kind == "real":
            keywords[option["name"]] = float(default)
            assert option["min"] <= float(default) <= option["max"], option["name"]
        elif kind == "integer":
            keywords[option["name"]] = int(default)
        elif kind == "choice":
            assert default in option["choices"], option["name"]
            keywords[option["name"]] = default
        elif kind == "text" and default:
            keywords[option["name"]] = default
        else:
            assert kind == "text", f"{env_id}: unexpected type {kind} of {option['name']}"
    pairs = to_env_options(env_id, keywords)
    assert [name for name, _ in pairs] == list(keywords)
    if "-Mock-" in env_id:
        _core.Env(env_id, pairs)  # parses and checks every option
