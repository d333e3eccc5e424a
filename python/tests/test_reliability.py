"""Issue 26 from Python: the same checkpoint gate and the same setting bounds as the
command line (one validation path), with the same messages."""

import json
import struct
from pathlib import Path

import numpy as np
import pytest

import upkie_rl

MODEL = Path(__file__).resolve().parents[2] / "tests" / "data" / "policies" / \
    "pendulum_bullet_seed0.ckpt"


def crc32c(data: bytes) -> int:
    crc = 0xFFFFFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ (0x82F63B78 if crc & 1 else 0)
    return crc ^ 0xFFFFFFFF


def crafted(tmp_path, name, change_header=None, change_tensors=None):
    """The stored model with a changed header or tensor bytes, and a valid CRC."""
    data = MODEL.read_bytes()
    (size,) = struct.unpack("<Q", data[8:16])
    header = json.loads(data[16:16 + size])
    tensors = bytearray(data[16 + size:-4])
    if change_header:
        change_header(header)
    if change_tensors:
        change_tensors(tensors)
    text = json.dumps(header).encode()
    body = b"UPKIERL1" + struct.pack("<Q", len(text)) + text + bytes(tensors)
    path = tmp_path / name
    path.write_bytes(body + struct.pack("<I", crc32c(body)))
    return path


def test_nan_weights_are_refused_not_acted_on(tmp_path):
    def nan_first_parameter(tensors):
        # Three tensors of equal size, in name order: the two Adam moments, then
        # policy.parameters.
        offset = 2 * len(tensors) // 3
        tensors[offset:offset + 4] = struct.pack("<f", float("nan"))
    path = crafted(tmp_path, "nan.ckpt", change_tensors=nan_first_parameter)
    with pytest.raises(upkie_rl.CheckpointError, match="tensor 'policy.parameters' value 0"):
        upkie_rl.load_policy(path)


def test_other_versions_are_refused_as_on_the_command_line(tmp_path):
    path = crafted(tmp_path, "v2.ckpt", change_header=lambda h: h.update(version=2))
    with pytest.raises(upkie_rl.CheckpointError, match="version 2 is not the version 1"):
        upkie_rl.load_policy(path)


def test_extra_provenance_keys_are_tolerated(tmp_path):
    path = crafted(tmp_path, "provenance.ckpt",
                   change_header=lambda h: h.update(provenance={"tool": "sb3"}))
    policy = upkie_rl.load_policy(path)
    assert np.isfinite(policy(np.zeros(4, dtype=np.float32))).all()


def test_vector_env_sizes_are_bounded_before_anything_is_built():
    with pytest.raises(ValueError, match=r"num_envs: 3000000 is outside \[1, 4096\]"):
        upkie_rl.make_vec("Upkie-Bullet-Pendulum", 3_000_000)
