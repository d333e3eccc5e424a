"""Each failure kind the fuzzing (fuzz_inputs.py) found, as a one-line error: the readers of
SB3 zips and VecNormalize files, and the public functions given an id that is not a string."""

import gc
import json
import os
import subprocess
import sys
import zipfile

import pytest

import upkie_rl
from upkie_rl.safe_pickle import UnsafePickleError, load_allowlisted
from upkie_rl import sb3_convert
from upkie_rl.sb3_convert import ConversionError, describe_sb3, import_sb3

ENV_ID = "Upkie-Bullet-Pendulum"
DEEP = b"[" * 100_000 + b"]" * 100_000


def sb3_zip(path, data: bytes, **members):
    with zipfile.ZipFile(path, "w") as archive:
        archive.writestr("data", data)
        archive.writestr("policy.pth", b"\x00")
        for name, content in members.items():
            archive.writestr(name, content)
    return path


def ppo_data(**fields) -> bytes:
    data = {"clip_range": 0.2, "n_epochs": 10, "batch_size": 64, "policy_class": {
        "__init__": "<function ActorCriticPolicy.__init__ at 0x1>"}}
    data.update(fields)
    return json.dumps(data).encode()


def test_deeply_nested_data_is_refused_in_one_line_by_the_command(tmp_path):
    path = sb3_zip(tmp_path / "deep.zip", DEEP)
    for command in (["info", path], ["import", path, "--env", ENV_ID, "-o", tmp_path / "m.ckpt"]):
        result = subprocess.run([sys.executable, "-m", "upkie_rl.sb3_convert", *map(str, command)],
                                capture_output=True, text=True, env=os.environ.copy())
        assert result.returncode == 1, result.stderr
        assert result.stderr.splitlines() == [
            f"upkie_rl.sb3_convert: error: {path}: 'data' nests too deeply to be SB3's JSON"]


def test_deeply_nested_provenance_member_is_refused(tmp_path):
    path = sb3_zip(tmp_path / "deep.zip", ppo_data(), **{"upkie_rl.json": DEEP})
    with pytest.raises(ConversionError, match="'upkie_rl.json' nests too deeply"):
        describe_sb3(path)


def test_policy_kwargs_that_is_not_an_object_is_refused(tmp_path):
    path = sb3_zip(tmp_path / "kwargs.zip", ppo_data(policy_kwargs=[None]))
    with pytest.raises(ConversionError, match="policy_kwargs is a list, not an object"):
        import_sb3(path, ENV_ID, tmp_path / "m.ckpt")


def test_class_names_with_newlines_are_quoted_onto_one_line(tmp_path):
    path = sb3_zip(tmp_path / "names.zip", ppo_data(policy_kwargs={
        "features_extractor_class": "\n"}))
    with pytest.raises(ConversionError) as error:
        import_sb3(path, ENV_ID, tmp_path / "m.ckpt")
    assert len(str(error.value).splitlines()) == 1
    assert "features extractor '\\n'; only FlattenExtractor" in str(error.value)
    # The activation's name reaches its message the same way, cut to 60 characters.
    assert sb3_convert._class_name("<class 'x'\n>" + "y" * 100) == repr("<class 'x'\n>" + "y" * 48)


@pytest.mark.parametrize("shape", ["(", "[" * 5000, "(1.5,)", "('a',)"],
                         ids=["unclosed", "deep", "float", "text"])
def test_unreadable_space_shape_is_refused(tmp_path, shape):
    box = {":type:": "<class 'gymnasium.spaces.box.Box'>", "_shape": shape, "dtype": "float32"}
    path = sb3_zip(tmp_path / "shape.zip", ppo_data(observation_space=box))
    with pytest.raises(ConversionError, match="observation_space has shape .*only flat vectors"):
        import_sb3(path, ENV_ID, tmp_path / "m.ckpt")


def test_pickle_error_spanning_lines_becomes_one_line(tmp_path):
    path = tmp_path / "persistent.pkl"
    path.write_bytes(b"P0\n.")  # PERSID: pickle's message for it spans two lines
    with pytest.raises(UnsafePickleError) as raised:
        load_allowlisted(path)
    assert "\n" not in str(raised.value) and "persistent id" in str(raised.value)


def test_bytearray_longer_than_the_file_is_refused_and_nothing_is_printed(tmp_path, capfd):
    path = tmp_path / "bytearray.pkl"
    path.write_bytes(b"\x96 \x108v\xb2\x10\xfc ")  # BYTEARRAY8 of 277 TB, found by fuzzing
    with pytest.raises(UnsafePickleError) as raised:
        load_allowlisted(path)
    assert "\n" not in str(raised.value) and "bytearray8" in str(raised.value)
    gc.collect()  # CPython printed its SystemError when the collector freed the bytearray
    assert capfd.readouterr().err == ""


class _GeneratorPickledByClass:
    """Pickles as NumPy 2.2 pickles a generator's PCG64: the class named, then its state."""

    def __reduce__(self):
        import numpy as np
        return (np.random.PCG64, (), {"bit_generator": "PCG64", "state": {"state": 1, "inc": 3}})


def test_a_random_generator_named_by_its_class_is_read_as_a_record(tmp_path):
    import pickle
    path = tmp_path / "vecnormalize.pkl"
    path.write_bytes(pickle.dumps({"np_random": _GeneratorPickledByClass()}))
    loaded = load_allowlisted(path)
    record = loaded["np_random"]
    assert isinstance(record, upkie_rl.safe_pickle.InertRecord)
    assert record.state["state"] == {"state": 1, "inc": 3}


@pytest.mark.parametrize("make", [
    lambda: upkie_rl.env_options(None),
    lambda: upkie_rl.UpkieEnv(None),
    lambda: upkie_rl.make_vec(3, 1),
    lambda: upkie_rl.evaluation_start_options(["Upkie-Bullet-Pendulum"]),
])
def test_id_that_is_not_a_string_is_a_one_line_type_error(make):
    with pytest.raises(TypeError) as raised:
        make()
    assert str(raised.value).startswith("env_id: ") and "\n" not in str(raised.value)


@pytest.mark.parametrize("make", [
    lambda: upkie_rl.env_options("Upkie\nPendulum"),
    lambda: upkie_rl.make_vec("Upkie-Mock-Pendulum\r\x01", 1),
    lambda: upkie_rl.UpkieEnv("Upkie-Mock-Pendulum", **{"fall\npitch": 1.0}),
    lambda: upkie_rl.UpkieEnv("\n", render_mode=float("nan")),
], ids=["env_options", "make_vec", "option_name", "render_mode"])
def test_control_characters_in_an_error_are_escaped_onto_one_line(make):
    with pytest.raises(ValueError) as raised:
        make()
    message = str(raised.value)
    assert "\n" not in message and "\r" not in message, message
    assert "\\n" in message or "\\r" in message, message
