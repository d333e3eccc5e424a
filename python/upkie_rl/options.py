"""Keyword arguments of ``gym.make`` turned into the registry's ``key=value`` options.

The C++ registry parses and checks every option (bounds, choices) and names the bad one;
this module only checks the Python type against the option's declared type, so that
``frequency="fast"`` or ``regulate_frequency=1`` fail with a TypeError naming the option
rather than being silently stringified.
"""

from __future__ import annotations

import functools
import json
import numbers
from typing import Any, Dict, List, Tuple

from . import _core
from .arguments import env_id_argument


@functools.lru_cache(maxsize=None)
def option_table(env_id: str) -> Dict[str, dict]:
    """The options ``env_id`` accepts, by name (name, type, help, default, min, max, choices)."""
    return {option["name"]: option for option in _core.env_options(env_id)}


def _format(env_id: str, option: dict, value: Any) -> str:
    name, kind = option["name"], option["type"]
    where = f"{env_id}: option {name}"
    if kind == "choice":
        if isinstance(value, bool) and set(option["choices"]) == {"true", "false"}:
            return "true" if value else "false"
        if isinstance(value, str):
            return value
        raise TypeError(f"{where} expects one of {option['choices']}, got {value!r}")
    if kind == "text":
        if isinstance(value, str):
            return value
        raise TypeError(f"{where} expects a string, got {type(value).__name__} {value!r}")
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        expected = "an integer" if kind == "integer" else "a real number"
        raise TypeError(f"{where} expects {expected}, got {type(value).__name__} {value!r}")
    if kind == "integer":
        if isinstance(value, numbers.Integral):
            return str(int(value))
        if float(value).is_integer():
            return str(int(float(value)))
        raise TypeError(f"{where} expects an integer, got {value!r}")
    return repr(float(value))


def to_env_options(env_id: str, options: Dict[str, Any]) -> List[Tuple[str, str]]:
    """Registry options of keyword arguments; raises ValueError on an unknown name (listing
    the valid ones) and TypeError on a value of the wrong type or an id that is not a string."""
    table = option_table(env_id_argument(env_id))
    pairs = []
    for name, value in options.items():
        if name not in table:
            # json.dumps: the name in quotes, a newline in it escaped (one line).
            raise ValueError(
                f"{env_id}: unknown option {json.dumps(str(name), ensure_ascii=False)}; "
                f'valid options: {", ".join(table)}'
            )
        pairs.append((name, _format(env_id, table[name], value)))
    return pairs
