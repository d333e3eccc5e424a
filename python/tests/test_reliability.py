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


def test_finite_weights_that_overflow_are_refused(tmp_path):
    def huge_first_parameter(tensors):
        offset = 2 * len(tensors) // 3
        tensors[offset:offset + 4] = struct.pack("<f", 1e36)
    path = crafted(tmp_path, "huge.ckpt", change_tensors=huge_first_parameter)
    with pytest.raises(upkie_rl.CheckpointError,
                       match=r"actor layer 0 can reach 1e\+37 \(limit 1e\+30\): "
                             r"tensor 'policy.parameters' value 0 is 1e\+36"):
        upkie_rl.load_policy(path)


def test_an_action_that_overflows_is_refused_not_returned(tmp_path):
    """Without normalisation the gate checks raw observations up to 1e6; beyond, weights
    it accepts can overflow, and the policy raises instead of returning NaN."""
    def overflowing_actor(tensors):
        offset = 2 * len(tensors) // 3  # policy.parameters: 4-64-64-1 actor first
        values = [1e18] * 256 + [0.0] * 64 + [1.0] * 4096 + [0.0] * 64 + \
            [1.0, -1.0] * 32 + [0.0]
        tensors[offset:offset + 4 * len(values)] = struct.pack(f"<{len(values)}f", *values)
    path = crafted(tmp_path, "overflow.ckpt", change_header=lambda h: h.pop("normalization"),
                   change_tensors=overflowing_actor)
    policy = upkie_rl.load_policy(path)
    assert np.isfinite(policy(np.array([0.0, 1e6, 0.0, 0.0], dtype=np.float32))).all()
    with pytest.raises(upkie_rl.PolicyOutputError, match=r"component 0 \(ground_velocity\) is nan"):
        policy(np.array([0.0, 1e30, 0.0, 0.0], dtype=np.float32))


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


@pytest.mark.parametrize("name, change, message", [
    ("v2.ckpt", dict(change_header=lambda h: h.update(version=2)),
     "checkpoint version 2 is not the version 1 this build reads"),
    ("nan.ckpt", dict(change_tensors=lambda t: t.__setitem__(
        slice(2 * len(t) // 3, 2 * len(t) // 3 + 4), struct.pack("<f", float("nan")))),
     "tensor 'policy.parameters' value 0 is nan"),
])
def test_model_file_readers_go_through_the_gate(tmp_path, name, change, message):
    """read_model_checkpoint (model_provenance, the SB3 export) and export_onnx refuse what
    load_policy refuses, with the gate's message naming the file."""
    from upkie_rl import sb3_convert

    path = crafted(tmp_path, name, **change)
    expected = f"checkpoint {path}: {message}"
    with pytest.raises(upkie_rl.CheckpointError) as refused:
        upkie_rl.load_policy(path)
    assert str(refused.value) == expected
    for reader in (lambda: upkie_rl._core.read_model_checkpoint(str(path)),
                   lambda: upkie_rl.model_provenance(path),
                   lambda: upkie_rl.export_onnx(path, tmp_path / "never.onnx"),
                   lambda: sb3_convert.export_sb3(path, tmp_path / "never.zip")):
        with pytest.raises(upkie_rl.CheckpointError) as refused:
            reader()
        assert str(refused.value) == expected
    assert not (tmp_path / "never.onnx").exists() and not (tmp_path / "never.zip").exists()


def test_a_flipped_byte_is_refused_by_every_model_file_reader(tmp_path):
    data = bytearray(MODEL.read_bytes())
    data[len(data) // 2] ^= 0x01
    path = tmp_path / "flipped.ckpt"
    path.write_bytes(bytes(data))
    with pytest.raises(upkie_rl.CheckpointError) as refused:
        upkie_rl.load_policy(path)
    expected = str(refused.value)
    assert "flipped.ckpt" in expected
    for reader in (lambda: upkie_rl._core.read_model_checkpoint(str(path)),
                   lambda: upkie_rl.export_onnx(path, tmp_path / "never.onnx")):
        with pytest.raises(upkie_rl.CheckpointError, match="flipped.ckpt") as refused:
            reader()
        assert str(refused.value) == expected
