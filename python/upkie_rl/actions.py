"""Checks and conversion of user actions to the float32 arrays the C++ side takes."""

from __future__ import annotations

import numpy as np


def as_action_array(action, shape, what: str = "action") -> np.ndarray:
    """A C-contiguous float32 copy-if-needed of ``action``.

    Raises TypeError on a non-numeric dtype and ValueError on a wrong shape (a scalar is
    accepted for a one-component action). NaN and infinity are checked by the C++ side,
    which names the component.
    """
    array = np.asarray(action)
    if array.dtype.kind not in "fiub":
        raise TypeError(f"{what} must be real numbers, got dtype {array.dtype}")
    if array.shape != tuple(shape):
        if array.size == int(np.prod(shape)) and (array.ndim == 0 or array.shape[-1:] == (1,)):
            array = array.reshape(shape)
        else:
            raise ValueError(f"{what} has shape {array.shape}, expected {tuple(shape)}")
    return np.ascontiguousarray(array, dtype=np.float32)
