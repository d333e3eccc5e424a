"""Reading Stable-Baselines3's ``VecNormalize`` statistics file without running pickled code.

``VecNormalize.save`` pickles the whole wrapper. A pickle may name any importable callable,
so loading one with ``pickle.load`` runs whatever code its author chose. This reader
resolves only an allowlist of names, and none of them to SB3 or Gymnasium classes:

- ``VecNormalize``, ``RunningMeanStd`` and Gymnasium's ``Box`` become inert records that
  only keep the state they are given (no constructor or ``__setstate__`` of theirs runs);
- NumPy's own array and scalar reconstruction (``_reconstruct``, ``ndarray``, ``dtype``,
  ``scalar``), which build arrays from bytes, and its random-generator constructors, which
  also become inert records.

Any other name raises ``UnsafePickleError`` naming it; so does a file over ``MAX_BYTES``, and
a file whose opcodes ``pickletools`` cannot walk (a length past the end of the data, which
would otherwise be allocated first and found missing after).
"""

from __future__ import annotations

import importlib
import io
import pickle
import pickletools
from pathlib import Path
from typing import Union

import numpy as np

#: Largest statistics file read, in bytes (a real one takes a few kilobytes).
MAX_BYTES = 16 << 20


class UnsafePickleError(ValueError):
    """A pickle that names something outside the allowlist, or that cannot be read."""


class InertRecord:
    """Stands for an allowed class: keeps its pickled state in ``state``, runs nothing."""

    def __init__(self, *args, **kwargs):
        self.args = args
        self.state = {}

    def __setstate__(self, state):
        self.state = state if isinstance(state, dict) else {"state": state}


def _inert_factory(*args, **kwargs):
    return InertRecord(*args, **kwargs)


_NUMPY_CORE = ("numpy.core.multiarray", "numpy._core.multiarray")
# numpy's pickles name these private functions; numpy's stubs do not declare them.
_MULTIARRAY = importlib.import_module("numpy.core.multiarray")
_ALLOWED = {
    **{(module, "_reconstruct"): _MULTIARRAY._reconstruct for module in _NUMPY_CORE},
    **{(module, "scalar"): _MULTIARRAY.scalar for module in _NUMPY_CORE},
    ("numpy", "ndarray"): np.ndarray,
    ("numpy", "dtype"): np.dtype,
    ("stable_baselines3.common.vec_env.vec_normalize", "VecNormalize"): InertRecord,
    ("stable_baselines3.common.running_mean_std", "RunningMeanStd"): InertRecord,
    ("gymnasium.spaces.box", "Box"): InertRecord,
    ("numpy.random._pickle", "__generator_ctor"): _inert_factory,
    ("numpy.random._pickle", "__bit_generator_ctor"): _inert_factory,
    ("numpy.random._pickle", "__randomstate_ctor"): _inert_factory,
    # Newer NumPy (Debian 13's 2.2) pickles a space's random generator by naming its bit
    # generator's class itself; kept as an inert record, like the constructors above.
    **{(f"numpy.random._{module}", name): InertRecord
       for module, name in (("pcg64", "PCG64"), ("pcg64", "PCG64DXSM"), ("mt19937", "MT19937"),
                            ("philox", "Philox"), ("sfc64", "SFC64"), ("generator", "Generator"))},
    # ... and its seed sequence through Cython's unpickling function.
    ("numpy.random.bit_generator", "__pyx_unpickle_SeedSequence"): _inert_factory,
    ("numpy.random.bit_generator", "SeedSequence"): InertRecord,
}


class _Reader:
    """A byte stream with ``read`` and ``readline`` only. Why: given a stream with
    ``readinto`` (io.BytesIO), CPython's unpickler leaves a buffer exported from a
    bytearray it failed to fill, and the garbage collector later prints "SystemError:
    deallocated bytearray object has exported buffers" (found by fuzz_inputs.py)."""

    def __init__(self, data: bytes):
        self._stream = io.BytesIO(data)

    def read(self, size: int = -1) -> bytes:
        return self._stream.read(size)

    def readline(self, size: int = -1) -> bytes:
        return self._stream.readline(size)


class _AllowlistUnpickler(pickle.Unpickler):
    def find_class(self, module, name):
        try:
            return _ALLOWED[(module, name)]
        except KeyError:
            raise UnsafePickleError(
                f"refusing to load {module}.{name}: a VecNormalize statistics file holds "
                "only VecNormalize, RunningMeanStd, Box and NumPy arrays"
            ) from None


def load_allowlisted(path: Union[str, Path]) -> object:
    """Unpickles ``path`` with the allowlist above; raises UnsafePickleError naming the file
    and the problem (too large, truncated, not a pickle, a name outside the allowlist)."""
    path = Path(path)
    size = path.stat().st_size
    if size > MAX_BYTES:
        raise UnsafePickleError(f"{path}: {size} bytes, more than the {MAX_BYTES} allowed")
    data = path.read_bytes()
    try:
        for _ in pickletools.genops(data):  # every length checked before anything is built
            pass
        return _AllowlistUnpickler(_Reader(data)).load()
    except UnsafePickleError as error:
        raise UnsafePickleError(f"{path}: {error}") from None
    except Exception as error:  # Any malformed pickle: truncated, bad opcode, bad args.
        reason = " ".join(str(error).split())  # pickle's messages may span lines
        raise UnsafePickleError(
            f"{path}: not a readable VecNormalize pickle ({type(error).__name__}: {reason})"
        ) from None
