"""Test session settings shared by every test file.

Under NumPy 2 (the newest-Gymnasium venv of scripts/install-deps.sh), Debian's torch 1.13,
which the venv sees through its system site packages, was built against NumPy 1: it
imports, but `torch.from_numpy` raises "Numpy is not available", so SB3 and the TorchScript
tests would fail for a reason that is not the package's. There torch is hidden from the
tests (`import torch` raises ImportError, so `pytest.importorskip` skips them) and the
session header says why; they run in Debian's interpreter, under NumPy 1.26.
"""

import importlib.metadata
import sys

import numpy as np


def _major_minor(version: str):
    parts = version.split(".")
    return int(parts[0]), int("".join(c for c in parts[1] if c.isdigit()) or 0)


def _torch_predates_numpy_2() -> str:
    """Why torch cannot exchange arrays with this NumPy, or "" when it can (or is absent)."""
    if _major_minor(np.__version__)[0] < 2:
        return ""
    try:
        torch_version = importlib.metadata.version("torch")
    except importlib.metadata.PackageNotFoundError:
        return ""
    if _major_minor(torch_version) >= (2, 3):  # the first torch built for NumPy 2
        return ""
    return (f"torch {torch_version} was built against NumPy 1 and cannot exchange arrays with "
            f"NumPy {np.__version__}: torch, SB3 and TorchScript tests are skipped here")


_TORCH_HIDDEN_BECAUSE = _torch_predates_numpy_2()
if _TORCH_HIDDEN_BECAUSE:
    sys.modules["torch"] = None  # type: ignore[assignment]  # `import torch` raises ImportError


def pytest_report_header(config):
    return f"numpy {np.__version__}" + (f"; {_TORCH_HIDDEN_BECAUSE}" if _TORCH_HIDDEN_BECAUSE else "")
