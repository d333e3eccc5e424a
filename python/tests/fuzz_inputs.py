"""Fuzzing the package's readers and public functions with Hypothesis: no bad input may end
in anything but a one-line error of the kinds each function documents.

Each target below takes inputs drawn by Hypothesis and calls the package as a user would;
``expect_one_line_error`` is the oracle: the call returns, or raises one of the documented
exception kinds with a one-line message. Anything else (RecursionError, AttributeError, an
exception whose message spans lines, ...) is a failure that Hypothesis shrinks and reports.

``test_fuzz_inputs.py`` runs every target on a few hundred inputs in the test suite;
``make fuzz-python`` runs them on FUZZ_PYTHON_TOTAL inputs in all (1M by default), shared
by SHARES:

    python3 python/tests/fuzz_inputs.py --total 1000000 [--targets sb3_data_fields ...]
"""

from __future__ import annotations

import argparse
import atexit
import io
import json
import os
import pickle
import shutil
import sys
import tempfile
import time
import traceback
import zipfile
from pathlib import Path
from typing import Callable, Dict, Tuple, Type

import numpy as np
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import upkie_rl
from upkie_rl import sb3_convert
from upkie_rl.safe_pickle import load_allowlisted

ROOT = Path(__file__).resolve().parents[2]
POLICY = ROOT / "tests" / "data" / "policies" / "pendulum_bullet_seed0.ckpt"
# The environment imports are checked against: the mock backend, made in microseconds.
ENV_ID = "Upkie-Mock-Pendulum"
# The file readers' documented errors: ValueError (ConversionError, UnsafePickleError,
# upkie_rl's CheckpointError and ModelError) and a missing file; the public functions may
# also raise TypeError (a wrong type) and IndexError (an index out of range).
READER_ERRORS: Tuple[Type[BaseException], ...] = (ValueError, FileNotFoundError)
ARGUMENT_ERRORS: Tuple[Type[BaseException], ...] = READER_ERRORS + (TypeError, IndexError)
# In memory where there is a tmpfs: every input is written as a file.
SCRATCH = Path(tempfile.mkdtemp(prefix="upkie-rl-fuzz-",
                                dir="/dev/shm" if os.path.isdir("/dev/shm") else None))
atexit.register(shutil.rmtree, SCRATCH, ignore_errors=True)


# Inputs run so far (Hypothesis's examples, shrinking included), printed every
# PROGRESS_EVERY by a long run, so that a run stopped early still says what it covered.
INPUTS_RUN = 0
PROGRESS_EVERY = 0


def expect_one_line_error(call: Callable[[], object], allowed=READER_ERRORS) -> None:
    """Calls ``call``; it returns, or raises an ``allowed`` error of one non-empty line."""
    try:
        call()
    except allowed as error:
        message = str(error)
        assert message and "\n" not in message, f"{type(error).__name__}: {message!r}"


# ---------------------------------------------------------------------------------------
# Inputs

JSON_LEAVES = st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=20)
JSON_VALUES = st.recursive(
    JSON_LEAVES,
    lambda children: st.lists(children, max_size=4)
    | st.dictionaries(st.text(max_size=12), children, max_size=4),
    max_leaves=12,
)


@st.composite
def deep_json(draw) -> str:
    """Arrays or objects nested up to 200,000 deep, closed or not."""
    depth = draw(st.integers(1, 200_000))
    opener, closer = draw(st.sampled_from([("[", "]"), ('{"a":', "}")]))
    tail = closer * depth if draw(st.booleans()) else ""
    return opener * depth + ("0" if opener == "[" else "0") + tail


# Values for the entries that SB3's `data` holds, valid and not.
BOX_ENTRY = st.fixed_dictionaries({
    ":type:": st.sampled_from(["<class 'gymnasium.spaces.box.Box'>", "Discrete"]) | JSON_VALUES,
    "_shape": st.sampled_from(["(5,)", "(2, 2)", "()", "(", "[1]", "(a,)"]) | JSON_VALUES,
    "dtype": st.sampled_from(["float32", "float64"]) | JSON_VALUES,
    "low": st.sampled_from(["[-inf -inf -inf -inf -inf]", "[...]", "[1 2]"]) | JSON_VALUES,
    "high": st.sampled_from(["[inf inf inf inf inf]", "[x]"]) | JSON_VALUES,
})
SB3_DATA = st.fixed_dictionaries(
    {"clip_range": JSON_VALUES, "n_epochs": JSON_VALUES, "batch_size": JSON_VALUES},
    optional={
        "policy_class": st.fixed_dictionaries({
            "__init__": st.sampled_from(["<function ActorCriticPolicy.__init__ at 0x1>"])
            | JSON_VALUES}) | JSON_VALUES,
        "use_sde": JSON_VALUES,
        "policy_kwargs": st.fixed_dictionaries({}, optional={
            "activation_fn": st.sampled_from(["<class 'torch.nn.ReLU'>", "<class 'Mish'>"])
            | JSON_VALUES,
            "features_extractor_class": JSON_VALUES,
            "squash_output": JSON_VALUES,
        }) | JSON_VALUES,
        "observation_space": BOX_ENTRY | JSON_VALUES,
        "action_space": BOX_ENTRY | JSON_VALUES,
        "num_timesteps": JSON_VALUES,
        "seed": JSON_VALUES,
    },
)


def write_zip(members: Dict[str, bytes]) -> Path:
    path = SCRATCH / "model.zip"
    with zipfile.ZipFile(path, "w") as archive:
        for name, content in members.items():
            archive.writestr(name, content)
    return path


def write_bytes(content: bytes, name: str) -> Path:
    path = SCRATCH / name
    path.write_bytes(content)
    return path


def convert_zip(path: Path) -> None:
    """What `sb3_convert info` and `import` do with a zip."""
    expect_one_line_error(lambda: sb3_convert.describe_sb3(path))
    expect_one_line_error(lambda: sb3_convert.import_sb3(path, ENV_ID, SCRATCH / "out.ckpt"))


# A VecNormalize-like pickle: records of the allowlisted classes holding fuzzed state.
RECORD_CLASSES = [("stable_baselines3.common.vec_env.vec_normalize", "VecNormalize"),
                  ("stable_baselines3.common.running_mean_std", "RunningMeanStd"),
                  ("gymnasium.spaces.box", "Box"), ("builtins", "eval")]
PICKLE_LEAVES = JSON_LEAVES | st.builds(np.array, st.lists(st.floats(), max_size=4)) | st.builds(
    np.float64, st.floats())


class Record:
    """Pickled as an instance of `cls` (module, name) with `state`, by record_pickle."""

    def __init__(self, cls: Tuple[str, str], state: object) -> None:
        self.cls, self.state = cls, state


PICKLE_VALUES = st.recursive(
    PICKLE_LEAVES,
    lambda children: st.dictionaries(st.sampled_from(
        ["norm_obs", "norm_reward", "clip_obs", "clip_reward", "gamma", "epsilon", "obs_rms",
         "ret_rms", "mean", "var", "count", "norm_obs_keys"]) | st.text(max_size=5), children,
        max_size=8)
    | st.lists(children, max_size=3)
    | st.builds(Record, st.sampled_from(RECORD_CLASSES), children),
    max_leaves=20,
)


def record_pickle(value: object) -> bytes:
    """Protocol-2 pickle opcodes of `value`, Records as GLOBAL + NEWOBJ + BUILD."""
    if isinstance(value, Record):
        module, name = value.cls
        return (b"c" + module.encode() + b"\n" + name.encode() + b"\n" + b")\x81"
                + record_pickle(value.state) + b"b")
    if isinstance(value, dict):
        items = b"".join(record_pickle(k) + record_pickle(v) for k, v in value.items())
        return b"}(" + items + b"u"
    if isinstance(value, list):
        return b"](" + b"".join(record_pickle(v) for v in value) + b"e"
    return pickle.dumps(value, protocol=2)[2:-1]  # without PROTO and STOP


# ---------------------------------------------------------------------------------------
# Targets: one input each, checked by the oracle.


@given(data=st.binary(max_size=200) | deep_json().map(str.encode)
       | JSON_VALUES.map(lambda v: json.dumps(v).encode()),
       provenance=st.none() | st.binary(max_size=50) | deep_json().map(str.encode))
def sb3_zip_members(data, provenance):
    """A zip whose `data` (and `upkie_rl.json`) are bytes, deep JSON or any JSON."""
    members = {"data": data, "policy.pth": b"\x00"}
    if provenance is not None:
        members[sb3_convert.PROVENANCE_MEMBER] = provenance
    convert_zip(write_zip(members))


@given(data=SB3_DATA)
def sb3_data_fields(data):
    """A zip whose `data` is SB3-shaped with any values in its fields."""
    convert_zip(write_zip({"data": json.dumps(data).encode(), "policy.pth": b"\x00"}))


@given(content=st.binary(max_size=300))
def zip_bytes(content):
    """Any bytes as a zip file."""
    convert_zip(write_bytes(content, "bytes.zip"))


@given(value=PICKLE_VALUES, size=st.integers(1, 6))
def vec_normalize_pickle(value, size):
    """A pickle of VecNormalize-like records holding any state."""
    path = write_bytes(b"\x80\x02" + record_pickle(value) + b".", "vecnormalize.pkl")
    expect_one_line_error(lambda: sb3_convert.read_vec_normalize(path, size))


@given(content=st.binary(max_size=300))
def pickle_bytes(content):
    """Any bytes as a VecNormalize file."""
    path = write_bytes(content, "bytes.pkl")
    expect_one_line_error(lambda: load_allowlisted(path))
    expect_one_line_error(lambda: sb3_convert.read_vec_normalize(path, 5))


POLICY_BYTES = POLICY.read_bytes()


@given(cut=st.integers(0, len(POLICY_BYTES)), flips=st.lists(
    st.tuples(st.integers(0, len(POLICY_BYTES) - 1), st.integers(1, 255)), max_size=4),
       suffix=st.sampled_from([".ckpt", ".onnx", ".bin"]))
def model_file(cut, flips, suffix):
    """A trained checkpoint, cut short and with bytes changed, read by every reader."""
    content = bytearray(POLICY_BYTES[:cut])
    for position, xor in flips:
        if position < len(content):
            content[position] ^= xor
    path = write_bytes(bytes(content), "model" + suffix)
    expect_one_line_error(lambda: upkie_rl.load_policy(path))
    expect_one_line_error(lambda: upkie_rl.model_provenance(path))
    expect_one_line_error(lambda: sb3_convert.export_sb3(path, SCRATCH / "export.zip"))


ENV_IDS = st.sampled_from(upkie_rl.registered_env_ids()) | st.text(max_size=30)
ANY_ARGUMENT = (JSON_LEAVES | st.integers(-2**70, 2**70) | st.just(float("nan"))
                | st.builds(np.int64, st.integers(-2**63, 2**63 - 1)) | st.binary(max_size=5))


@given(env_id=ENV_IDS | ANY_ARGUMENT, options=st.dictionaries(
    st.sampled_from(["frequency", "init_rand_pitch", "fall_pitch", "max_episode_steps"])
    | st.text(max_size=8), ANY_ARGUMENT, max_size=3))
def option_functions(env_id, options):
    """The registry's functions on any id and options."""
    expect_one_line_error(lambda: upkie_rl.env_options(env_id), ARGUMENT_ERRORS)
    expect_one_line_error(lambda: upkie_rl.evaluation_start_options(env_id, options),
                          ARGUMENT_ERRORS)


@given(env_id=st.sampled_from(["Upkie-Mock-Pendulum", "Upkie-Mock-Velocity"]) | ANY_ARGUMENT,
       num_envs=ANY_ARGUMENT, num_threads=st.none() | ANY_ARGUMENT, seed=ANY_ARGUMENT,
       options=st.dictionaries(st.sampled_from(
           ["frequency", "fall_pitch", "render_mode", "render_width", "autoreset_mode",
            "spine_observation"]) | st.text(max_size=8), ANY_ARGUMENT, max_size=2))
def make_functions(env_id, num_envs, num_threads, seed, options):
    """make_vec and UpkieEnv on any arguments (closed when made)."""
    def make_vec():
        upkie_rl.make_vec(env_id, num_envs, num_threads, seed, **options).close()

    def make_env():
        upkie_rl.UpkieEnv(env_id, **options).close()

    expect_one_line_error(make_vec, ARGUMENT_ERRORS)
    expect_one_line_error(make_env, ARGUMENT_ERRORS)


LOADED_POLICY = upkie_rl.load_policy(POLICY)


def filled_array(shape, dtype, fill) -> np.ndarray:
    with np.errstate(all="ignore"):  # casting NaN or 1e300 to an integer type is the point
        return np.full(shape, fill).astype(dtype, copy=False)


OBSERVATIONS = ANY_ARGUMENT | st.lists(ANY_ARGUMENT, max_size=6) | st.builds(
    filled_array,
    st.lists(st.integers(0, 6), max_size=3), st.sampled_from(
        [np.float32, np.float64, np.int8, np.uint64, np.bool_, np.complex64, object, str]),
    st.floats() | st.integers(-10, 10))


@given(observation=OBSERVATIONS, deterministic=ANY_ARGUMENT)
def policy_inputs(observation, deterministic):
    """A loaded policy's __call__ and predict on any observation."""
    expect_one_line_error(lambda: LOADED_POLICY(observation), ARGUMENT_ERRORS)
    expect_one_line_error(lambda: LOADED_POLICY.predict(observation, deterministic=deterministic),
                          ARGUMENT_ERRORS)


@given(argv=st.lists(st.sampled_from(["import", "export", "info", "--env", ENV_ID,
                                      "--output", "--env-option", "--vecnormalize", "a=b",
                                      "=", "/nonexistent"]) | st.text(max_size=10),
                     max_size=6))
def sb3_convert_main(argv):
    """`python3 -m upkie_rl.sb3_convert` on any arguments: a status, never an exception.
    (A model that converts takes half a second: the model readers are model_file's.)"""
    stderr = io.StringIO()
    streams, directory = (sys.stdout, sys.stderr), os.getcwd()
    sys.stdout, sys.stderr = io.StringIO(), stderr
    os.chdir(SCRATCH)  # where an --output it is given lands
    try:
        status = sb3_convert.main(argv)
    except SystemExit as exit:  # argparse's usage error
        status = exit.code
    finally:
        sys.stdout, sys.stderr = streams
        os.chdir(directory)
    assert status in (0, 1, 2), status
    assert "Traceback" not in stderr.getvalue()


# Each target's share of a run's inputs (`--total`): the cheaper a target's inputs, the
# more of them it gets (they cost about 1 ms for a policy's input to 12 ms for an SB3 zip
# whose data reaches the environment check).
SHARES = {"policy_inputs": 25, "zip_bytes": 15, "pickle_bytes": 15, "make_functions": 10,
          "option_functions": 10, "sb3_zip_members": 8, "vec_normalize_pickle": 6,
          "sb3_convert_main": 5, "model_file": 4, "sb3_data_fields": 2}

TARGETS = {function.__name__: function for function in (
    sb3_zip_members, sb3_data_fields, zip_bytes, vec_normalize_pickle, pickle_bytes,
    model_file, option_functions, make_functions, policy_inputs, sb3_convert_main)}


def run(name: str, examples: int) -> None:
    """Runs target `name` on `examples` inputs (no example database, no shrinking limit)."""
    target = TARGETS[name]
    inner = target.hypothesis.inner_test  # Hypothesis's hook for wrapping each example

    def counted(*args, **kwargs):
        global INPUTS_RUN
        INPUTS_RUN += 1
        if PROGRESS_EVERY and INPUTS_RUN % PROGRESS_EVERY == 0:
            print(f"  {INPUTS_RUN:,} inputs run ({name})", flush=True)
        return inner(*args, **kwargs)

    target.hypothesis.inner_test = counted
    configured = settings(max_examples=examples, deadline=None, database=None,
                          suppress_health_check=list(HealthCheck))(target)
    configured()


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--total", type=int, default=10_000,
                        help="inputs over the targets run, shared as SHARES says")
    parser.add_argument("--targets", nargs="*", default=list(TARGETS), choices=list(TARGETS))
    parser.add_argument("--progress", type=int, default=0, metavar="N",
                        help="print the count of calls checked every N")
    args = parser.parse_args()
    global PROGRESS_EVERY
    PROGRESS_EVERY = args.progress
    shares = sum(SHARES[name] for name in args.targets)
    total, failed = 0, []
    for name in args.targets:
        examples = max(1, args.total * SHARES[name] // shares)
        start = time.perf_counter()
        try:
            run(name, examples)
        except Exception as error:  # Hypothesis has printed the shrunk input: go on
            print(f"{name}: FAILED: {type(error).__name__}: {error}", flush=True)
            print("".join(traceback.format_exception(error)[-4:]), flush=True)
            for note in getattr(error, "__notes__", []):
                print(note, flush=True)
            failed.append(name)
            continue
        total += examples
        print(f"{name}: {examples:,} inputs in {time.perf_counter() - start:.0f} s, "
              "no failure", flush=True)
    print(f"{total:,} inputs without a failure ({INPUTS_RUN:,} run, shrinking included); failed: "
          f"{', '.join(failed) or 'none'}")
    return 1 if failed else 0


if __name__ == "__main__":
    os.environ.setdefault("PYTHONHASHSEED", "0")
    sys.exit(main())
