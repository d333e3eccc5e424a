"""The C++ error hierarchy as seen from Python: one root, built-in bases kept."""

import pytest

import upkie_rl

ERRORS = {
    "ModelError": RuntimeError,
    "SimulationDivergedError": RuntimeError,
    "InvalidCommandError": ValueError,
    "RenderError": RuntimeError,
    "SpineError": RuntimeError,
    "SpineTimeoutError": RuntimeError,
    "CheckpointError": ValueError,
    "OnnxError": ValueError,
    "PolicyOutputError": RuntimeError,
}


def test_every_error_derives_from_the_root_and_keeps_its_builtin_base():
    assert issubclass(upkie_rl.Error, RuntimeError)
    for name, builtin in ERRORS.items():
        error = getattr(upkie_rl, name)
        assert issubclass(error, upkie_rl.Error), name
        assert issubclass(error, builtin), name
        assert error.__module__ == "upkie_rl", name
    assert issubclass(upkie_rl.SpineTimeoutError, upkie_rl.SpineError)


def test_errors_raised_in_cpp_arrive_as_their_own_class(tmp_path):
    garbage = tmp_path / "garbage.ckpt"
    garbage.write_bytes(b"not a checkpoint")
    with pytest.raises(upkie_rl.CheckpointError, match="bad magic") as caught:
        upkie_rl.load_policy(garbage)
    assert isinstance(caught.value, upkie_rl.Error)
    with pytest.raises(upkie_rl.SpineError, match="upkie_rl_no_such_spine"):
        upkie_rl.UpkieEnv("Upkie-Spine-Pendulum", shm_name="/upkie_rl_no_such_spine", open_tries=1)
