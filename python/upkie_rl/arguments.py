"""Checks of the package's own keyword arguments (counts, seeds, sizes, indices, flags)
before they reach the bindings.

Each check raises one line naming the argument, its value and its range, in the words of
the C++ range checks (``num_envs: 3000000 is outside [1, 4096]``): TypeError for a value of
the wrong type (a float, NaN, a string, a bool where a count goes), ValueError (IndexError
for an index) for one out of range. The ranges are the C++ declarations'
(``_core.ARGUMENT_RANGES``), the command line's, so that pybind11 never meets an integer it
cannot convert and answers with its four-line "incompatible function arguments".
"""

from __future__ import annotations

import numbers
from typing import Any, Optional, Tuple, Type

import numpy as np

from . import _core


def integer_argument(
    name: str,
    value: Any,
    minimum: Optional[int] = None,
    maximum: Optional[int] = None,
    out_of_range: Type[Exception] = ValueError,
) -> int:
    """``value`` as an int, if it is an integer (numpy's included, bool excluded) in
    [minimum, maximum]; the range defaults to ``_core.ARGUMENT_RANGES[name]``."""
    if minimum is None or maximum is None:
        minimum, maximum = _core.ARGUMENT_RANGES[name]
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise TypeError(
            f"{name}: {value!r} is not an integer; expected one in [{minimum}, {maximum}]"
        )
    integer = int(value)
    if not minimum <= integer <= maximum:
        raise out_of_range(f"{name}: {integer} is outside [{minimum}, {maximum}]")
    return integer


def seed_argument(seed: Any) -> Optional[int]:
    """None, or a seed in [0, 2**64 - 1] (the C++ generators' seeds) as an int."""
    return None if seed is None else integer_argument("seed", seed)


def index_argument(index: Any, count: int) -> int:
    """An environment's index in [0, count - 1]; IndexError outside."""
    return integer_argument("index", index, 0, count - 1, out_of_range=IndexError)


def flag_argument(name: str, value: Any) -> bool:
    """``value`` if it is a bool (numpy's included): "yes" or 1 is not taken for True."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name}: {value!r} is not a bool (True or False)")
    return bool(value)


def render_size(width: Any, height: Any) -> Tuple[int, int]:
    """(width, height) of frames, checked against the renderer's bounds."""
    return integer_argument("render_width", width), integer_argument("render_height", height)


def env_id_argument(env_id: Any) -> str:
    """``env_id`` if it is a string (an id is checked by the registry); TypeError otherwise,
    before pybind11 answers with its four-line "incompatible function arguments", and
    ValueError for one with a newline or another unprintable character."""
    if not isinstance(env_id, str):
        raise TypeError(
            f"env_id: {env_id!r} is not a string; expected an id such as 'Upkie-Bullet-Pendulum'"
        )
    if not env_id.isprintable():  # no id has one; the messages that quote it stay one line
        raise ValueError(f"env_id: {env_id!r} holds unprintable characters; no id does")
    return env_id
