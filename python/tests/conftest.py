"""Test session settings shared by every test file.

Under NumPy 2 (the newest-Gymnasium venv of scripts/install-deps.sh), Debian's torch 1.13,
which the venv sees through its system site packages, was built against NumPy 1: it
imports, but `torch.from_numpy` raises "Numpy is not available". The tests that hand
arrays to torch (SB3 training and conversion, TorchScript) carry the marker
`needs_torch_numpy` and are skipped there, with that reason; they run in Debian's
interpreter, under NumPy 1.26. The session header names NumPy's version.
"""

import importlib.metadata

import numpy as np
import pytest


def _major_minor(version: str):
    parts = version.split(".")
    return int(parts[0]), int("".join(c for c in parts[1] if c.isdigit()) or 0)


def _torch_predates_this_numpy() -> str:
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
            f"NumPy {np.__version__}")


TORCH_NUMPY_PROBLEM = _torch_predates_this_numpy()


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "needs_torch_numpy: hands arrays to torch (skipped where torch predates NumPy)")


def pytest_report_header(config):
    return f"numpy {np.__version__}" + (f"; {TORCH_NUMPY_PROBLEM}" if TORCH_NUMPY_PROBLEM else "")


def pytest_collection_modifyitems(config, items):
    if not TORCH_NUMPY_PROBLEM:
        return
    skip = pytest.mark.skip(reason=TORCH_NUMPY_PROBLEM)
    for item in items:
        if item.get_closest_marker("needs_torch_numpy"):
            item.add_marker(skip)
