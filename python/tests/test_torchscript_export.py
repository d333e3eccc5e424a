"""The TorchScript export of a trained policy loads in Python with torch.jit.load.

The C++ test tests/rl/torchscript_export_test.cpp exports a policy, writes a case file
(model path, inputs, the actions our C++ code computes) and runs this file with
/usr/bin/python3 (Debian's python3-torch): `python3 test_torchscript_export.py CASE.json`.
Under pytest the test runs when UPKIE_RL_TORCHSCRIPT_CASE names such a case file and torch
is importable; otherwise it is skipped.
"""

import json
import os
import sys


def check_case(case_path):
    import torch

    with open(case_path, encoding="utf-8") as file:
        case = json.load(file)
    extra_files = {"metadata.json": ""}
    module = torch.jit.load(case["model"], _extra_files=extra_files)
    metadata = json.loads(extra_files["metadata.json"])
    assert metadata["env_id"] == case["env_id"], metadata
    assert len(metadata["observation_space"]["low"]) == len(case["inputs"][0])
    inputs = torch.tensor(case["inputs"], dtype=torch.float32)
    expected = torch.tensor(case["expected"], dtype=torch.float32)
    with torch.no_grad():
        batch = module(inputs)
        single = module(inputs[0])
    assert batch.shape == expected.shape, (batch.shape, expected.shape)
    assert torch.allclose(batch, expected, atol=1e-5), (batch, expected)
    assert torch.allclose(single, expected[0], atol=1e-5), (single, expected[0])
    low = torch.tensor(metadata["action_space"]["low"], dtype=torch.float32)
    high = torch.tensor(metadata["action_space"]["high"], dtype=torch.float32)
    huge = module(torch.full_like(inputs, 1e6))
    assert bool(((huge >= low) & (huge <= high)).all()), huge


def test_torchscript_export():
    import pytest

    case_path = os.environ.get("UPKIE_RL_TORCHSCRIPT_CASE")
    if not case_path:
        pytest.skip("UPKIE_RL_TORCHSCRIPT_CASE not set (the C++ test runs this check)")
    pytest.importorskip("torch")
    check_case(case_path)


if __name__ == "__main__":
    check_case(sys.argv[1])
    print("torchscript export: OK")
