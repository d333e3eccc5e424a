"""Stable-Baselines3 PPO models to and from upkie-rl models.

Import: a PPO ``.zip`` saved by SB3 (``MlpPolicy``, any activation upkie-rl's actor knows)
and, when given, its ``VecNormalize`` statistics file become a ``.ckpt`` that every
``upkie-rl`` command and ``upkie_rl.load_policy`` accept::

    python3 -m upkie_rl.sb3_convert import ppo.zip --env Upkie-Bullet-Pendulum \\
        --vecnormalize vecnormalize.pkl --output model.ckpt

Export: an upkie-rl ``.ckpt`` becomes a ``.zip`` that ``stable_baselines3.PPO.load`` loads
(plus a ``VecNormalize`` file when the model normalises observations)::

    python3 -m upkie_rl.sb3_convert export model.ckpt --output ppo.zip \\
        --vecnormalize vecnormalize.pkl

What is trusted: nothing in the input is executed. The zip's ``data`` is read as JSON (its
cloudpickled entries are never unpickled), ``policy.pth`` with ``torch.load(...,
weights_only=True)`` (tensors only), the VecNormalize file with an allowlist unpickler
(``upkie_rl.safe_pickle``). Sizes are bounded before anything is read whole.
"""

from __future__ import annotations

import argparse
import hashlib
import io
import json
import re
import sys
import zipfile
from pathlib import Path
from typing import Dict, List, Optional, Tuple, Union

import numpy as np

from . import _core
from .env import UpkieEnv
from .safe_pickle import InertRecord, load_allowlisted
from .vector import canonical_id

PathLike = Union[str, Path]

#: The zip member an export adds: the model's provenance, environment and options.
PROVENANCE_MEMBER = "upkie_rl.json"
#: Largest member of an SB3 zip read, in bytes (uncompressed; a policy takes kilobytes).
MAX_MEMBER_BYTES = 64 << 20
#: Most members an SB3 zip may have (SB3 writes six).
MAX_MEMBERS = 64

# SB3 activation classes (torch.nn, default parameters) and upkie-rl's names for them, from
# their one list (policy/activation.hpp): the actor is evaluated with the same function.
ACTIVATIONS = _core.activation_torch_names()
# The checkpoint header's keys and format, from their one declaration
# (policy/checkpoint_header.hpp), e.g. _KEY["NUM_TIMESTEPS"] == "num_timesteps".
_KEY = _core.checkpoint_header_keys()
# The normalisation state's keys (vec/normalization_state.hpp) and the provenance's
# (policy/provenance.hpp), from their one declaration the same way.
_NORM = _core.normalization_state_keys()
_PROV = _core.provenance_keys()
_CHECKPOINT_FORMAT, _CHECKPOINT_VERSION = _core.checkpoint_format()
_IMPORT_SOURCE = "upkie_rl.sb3_convert import"


class ConversionError(ValueError):
    """An input that cannot be converted; the message names the file and the reason."""


# ---------------------------------------------------------------------------------------
# Reading an SB3 zip


def _read_zip(path: Path) -> Dict[str, bytes]:
    try:
        with zipfile.ZipFile(path) as archive:
            members = archive.infolist()
            if len(members) > MAX_MEMBERS:
                raise ConversionError(f"{path}: {len(members)} members, not an SB3 model")
            contents = {}
            for member in members:
                if member.file_size > MAX_MEMBER_BYTES:
                    raise ConversionError(
                        f"{path}: member {member.filename} expands to {member.file_size} "
                        f"bytes, more than the {MAX_MEMBER_BYTES} allowed"
                    )
                contents[member.filename] = archive.read(member)
    except (zipfile.BadZipFile, zipfile.LargeZipFile, EOFError, OSError) as error:
        raise ConversionError(f"{path}: not a readable zip file ({error})") from None
    except (NotImplementedError, RuntimeError, ValueError) as error:
        if isinstance(error, ConversionError):
            raise
        raise ConversionError(f"{path}: unsupported zip file ({error})") from None
    for required in ("data", "policy.pth"):
        if required not in contents:
            raise ConversionError(f"{path}: no '{required}' member: not a model saved by SB3")
    return contents


def _json_member(contents: Dict[str, bytes], name: str, where: str):
    """The zip member ``name`` read as JSON; ConversionError for text that is not JSON or
    nests deeper than Python's parser recurses (a hostile ``[[[[...`` member)."""
    try:
        return json.loads(contents[name])
    except (UnicodeDecodeError, ValueError) as error:
        raise ConversionError(f"{where}: '{name}' is not JSON ({error})") from None
    except RecursionError:
        raise ConversionError(f"{where}: '{name}' nests too deeply to be SB3's JSON") from None


def _sb3_data(contents: Dict[str, bytes], where: str) -> dict:
    """The zip's ``data`` member: SB3's JSON object of the model's settings."""
    data = _json_member(contents, "data", where)
    if not isinstance(data, dict):
        raise ConversionError(f"{where}: 'data' is not a JSON object")
    return data


def _object(data: dict, key: str, where: str) -> dict:
    """The JSON object ``data[key]`` ({} when absent or null, as SB3 writes no kwargs)."""
    value = data.get(key)
    if value is None:
        return {}
    if not isinstance(value, dict):
        raise ConversionError(f"{where}: {key} is a {type(value).__name__}, not an object")
    return value


def _class_name(entry) -> str:
    """The class an SB3 data entry names ('<class 'torch.nn...ReLU'>' -> 'ReLU'), or the
    entry quoted and cut to 60 characters: it goes into one-line error messages."""
    match = re.search(r"([A-Za-z_][A-Za-z0-9_]*)'>$", str(entry))
    return match.group(1) if match else repr(str(entry)[:60])


def _policy_class_name(data: dict) -> str:
    entry = data.get("policy_class")
    if isinstance(entry, dict):
        match = re.match(r"<function (\w+)\.__init__", str(entry.get("__init__", "")))
        if match:
            return match.group(1)
    return "unknown"


def _parse_array(text, what: str, where: str) -> np.ndarray:
    """A float32 array from SB3's str() of one (e.g. '[-inf  1.5]')."""
    cleaned = str(text).replace("[", " ").replace("]", " ").split()
    if "..." in cleaned:
        raise ConversionError(f"{where}: {what} is summarised ('...'), cannot be compared")
    try:
        return np.array([float(value) for value in cleaned], dtype=np.float32)
    except ValueError:
        raise ConversionError(f"{where}: unreadable {what} {text!r}") from None


def _sb3_box(data: dict, key: str, where: str) -> Tuple[np.ndarray, np.ndarray]:
    entry = data.get(key)
    if not isinstance(entry, dict) or "gymnasium.spaces.box.Box" not in str(entry.get(":type:")):
        kind = entry.get(":type:") if isinstance(entry, dict) else type(entry).__name__
        raise ConversionError(f"{where}: {key} is {kind}, only Box spaces can be converted")
    try:
        shape = json.loads(str(entry.get("_shape", "null")).replace("(", "[").replace(",)", "]"))
    except (ValueError, RecursionError):
        shape = None
    if not isinstance(shape, list) or len(shape) != 1 or type(shape[0]) is not int:
        raise ConversionError(
            f"{where}: {key} has shape {entry.get('_shape')}; only flat vectors can be "
            "converted (image and multi-dimensional observations are not)"
        )
    if entry.get("dtype") != "float32":
        raise ConversionError(f"{where}: {key} has dtype {entry.get('dtype')}, expected float32")
    low = _parse_array(entry.get("low"), f"{key}.low", where)
    high = _parse_array(entry.get("high"), f"{key}.high", where)
    if low.shape != (shape[0],) or high.shape != (shape[0],):
        raise ConversionError(f"{where}: {key} bounds do not have {shape[0]} values")
    return low, high


def _activation(data: dict, where: str) -> str:
    kwargs = _object(data, "policy_kwargs", where)
    name = _class_name(kwargs.get("activation_fn", "<class 'Tanh'>"))  # SB3's default
    if name not in ACTIVATIONS:
        raise ConversionError(
            f"{where}: activation {name} has no upkie-rl equivalent "
            f"(supported: {', '.join(ACTIVATIONS)})"
        )
    return ACTIVATIONS[name]


def _check_ppo(data: dict, where: str) -> None:
    if not all(key in data for key in ("clip_range", "n_epochs", "batch_size")):
        raise ConversionError(
            f"{where}: not a PPO model (no clip_range/n_epochs/batch_size): only PPO's "
            "MlpPolicy can be converted"
        )
    policy = _policy_class_name(data)
    if policy != "ActorCriticPolicy":
        raise ConversionError(
            f"{where}: policy class {policy}; only PPO's MlpPolicy (ActorCriticPolicy) can "
            "be converted (not CnnPolicy, MultiInputPolicy or recurrent policies)"
        )
    if data.get("use_sde"):
        raise ConversionError(f"{where}: trained with gSDE (use_sde), which is not supported")
    kwargs = _object(data, "policy_kwargs", where)
    extractor = kwargs.get("features_extractor_class")
    if extractor is not None and _class_name(extractor) != "FlattenExtractor":
        raise ConversionError(
            f"{where}: features extractor {_class_name(extractor)}; only FlattenExtractor"
        )
    if str(kwargs.get("squash_output", "False")) not in ("False", "false", "0"):
        raise ConversionError(f"{where}: squash_output is not supported")


def _mlp(state: dict, prefix: str, input_size: int, where: str) -> List[Tuple]:
    """The (weight, bias) of nn.Sequential Linear layers 0, 2, 4, ... under `prefix`."""
    layers, index, size = [], 0, input_size
    while f"{prefix}.{index}.weight" in state:
        weight = state[f"{prefix}.{index}.weight"]
        bias = state.get(f"{prefix}.{index}.bias")
        if bias is None or weight.ndim != 2 or weight.shape[1] != size or bias.shape != (weight.shape[0],):
            raise ConversionError(f"{where}: layer {prefix}.{index} has inconsistent shapes")
        layers.append((weight, bias))
        size = weight.shape[0]
        index += 2
    return layers


def _policy_state(contents: Dict[str, bytes], where: str) -> Dict[str, np.ndarray]:
    import torch

    try:
        state = torch.load(io.BytesIO(contents["policy.pth"]), map_location="cpu", weights_only=True)
    except Exception as error:  # torch raises many types for a damaged or hostile file
        raise ConversionError(
            f"{where}: policy.pth is not a plain tensor state dict ({type(error).__name__}: "
            f"{str(error).splitlines()[0] if str(error) else ''})"
        ) from None
    if not isinstance(state, dict) or not all(
        isinstance(key, str) and isinstance(value, torch.Tensor) for key, value in state.items()
    ):
        raise ConversionError(f"{where}: policy.pth is not a state dict of tensors")
    return {key: value.detach().to(torch.float32).numpy() for key, value in state.items()}


def _flat_parameters(state, observation_size, action_size, where):
    """upkie-rl's flat parameter buffer (actor, critic, log std) and hidden sizes."""
    actor = _mlp(state, "mlp_extractor.policy_net", observation_size, where)
    critic = _mlp(state, "mlp_extractor.value_net", observation_size, where)
    actor_last = actor[-1][0].shape[0] if actor else observation_size
    critic_last = critic[-1][0].shape[0] if critic else observation_size
    expected = {
        "action_net.weight": (action_size, actor_last),
        "action_net.bias": (action_size,),
        "value_net.weight": (1, critic_last),
        "value_net.bias": (1,),
        "log_std": (action_size,),
    }
    for key, shape in expected.items():
        if key not in state or state[key].shape != shape:
            found = state[key].shape if key in state else "absent"
            raise ConversionError(f"{where}: {key} is {found}, expected shape {shape}")
    known = set(expected) | {
        f"mlp_extractor.{net}.{2 * i}.{kind}"
        for net, layers in (("policy_net", actor), ("value_net", critic))
        for i in range(len(layers))
        for kind in ("weight", "bias")
    }
    unknown = sorted(set(state) - known)
    if unknown:
        raise ConversionError(f"{where}: unexpected parameters {unknown[:5]} (not an MlpPolicy)")
    if not actor or not critic:
        raise ConversionError(f"{where}: actor and critic need at least one hidden layer")
    pieces = []
    for weight, bias in actor + [(state["action_net.weight"], state["action_net.bias"])]:
        pieces += [weight.ravel(), bias]
    for weight, bias in critic + [(state["value_net.weight"], state["value_net.bias"])]:
        pieces += [weight.ravel(), bias]
    pieces.append(state["log_std"])
    parameters = np.concatenate(pieces).astype(np.float32)
    if not np.all(np.isfinite(parameters)):
        raise ConversionError(f"{where}: parameters hold NaN or infinity")
    return parameters, [w.shape[0] for w, _ in actor], [w.shape[0] for w, _ in critic]


def read_vec_normalize(path: PathLike, observation_size: int) -> dict:
    """The normalisation state (the header's "normalization" entry) of a VecNormalize file,
    read with the allowlist unpickler."""
    path = Path(path)
    wrapper = load_allowlisted(path)
    if not isinstance(wrapper, InertRecord):
        raise ConversionError(f"{path}: not a VecNormalize pickle")
    state = wrapper.state

    def statistics(name, size):
        record = state.get(name)
        if not isinstance(record, InertRecord):
            raise ConversionError(f"{path}: {name} is not a RunningMeanStd (dict observations?)")
        # SB3 keeps the return statistics as shape () arrays: read them as one value.
        mean = np.asarray(record.state.get("mean"))  # SB3's RunningMeanStd attributes
        var = np.asarray(record.state.get("var"))
        if size == 1 and mean.shape == () and var.shape == ():
            mean, var = mean.reshape(1), var.reshape(1)
        count = record.state.get("count")
        if count is None:
            raise ConversionError(f"{path}: {name} has no sample count")
        if mean.dtype.kind != "f" or var.dtype.kind != "f" or mean.shape != (size,) or var.shape != (size,):
            raise ConversionError(f"{path}: {name} is not {size} floating-point means and variances")
        if not np.all(np.isfinite(mean)) or not np.all(var >= 0) or not np.isfinite(float(count)):
            raise ConversionError(f"{path}: {name} holds invalid statistics")
        return {_NORM["MEAN"]: mean.tolist(), _NORM["VAR"]: var.tolist(),
                _NORM["COUNT"]: float(count)}

    try:
        config = {
            _NORM["OBSERVATIONS"]: bool(state["norm_obs"]),
            _NORM["REWARDS"]: bool(state["norm_reward"]),
            _NORM["CLIP_OBSERVATIONS"]: float(state["clip_obs"]),
            _NORM["CLIP_REWARDS"]: float(state["clip_reward"]),
            _NORM["GAMMA"]: float(state["gamma"]),
            _NORM["EPSILON"]: float(state["epsilon"]),
        }
    except (KeyError, TypeError, ValueError) as error:
        raise ConversionError(f"{path}: VecNormalize field missing or malformed: {error}") from None
    if state.get("norm_obs_keys"):
        raise ConversionError(f"{path}: normalises dict observations, which cannot be converted")
    return {
        _NORM["CONFIG"]: config,
        _NORM["OBSERVATION_STATISTICS"]: statistics("obs_rms", observation_size),
        _NORM["RETURN_STATISTICS"]: statistics("ret_rms", 1),
    }


# ---------------------------------------------------------------------------------------
# Import


def _env_spaces(env_id: str, options: Dict[str, str]):
    """The environment's flat (low, high, names) observation and action spaces."""
    import gymnasium as gym

    env = gym.make(f"upkie_rl/{canonical_id(env_id)}", **{k: _typed(v) for k, v in options.items()})
    try:
        unwrapped = env.unwrapped
        if not isinstance(unwrapped, UpkieEnv):
            raise ConversionError(f"{env_id} is not an upkie_rl environment")
        core = unwrapped._core
        return core.observation_space, core.action_space
    finally:
        env.close()


def _typed(value):
    """An option read back from text (the header stores options as text)."""
    if not isinstance(value, str):
        return value
    for kind in (int, float):
        try:
            return kind(value)
        except ValueError:
            pass
    return value


def _check_against_env(name, bounds, space, where):
    low, high = bounds
    env_low, env_high, _ = space
    if env_low.shape != low.shape:
        raise ConversionError(
            f"{where}: the model's {name} has shape {low.shape}, the environment's "
            f"{env_low.shape}"
        )
    for what, mine, theirs in (("low", low, env_low), ("high", high, env_high)):
        differs = np.flatnonzero(mine != theirs.astype(np.float32))
        if differs.size:
            i = int(differs[0])
            raise ConversionError(
                f"{where}: the model's {name}.{what}[{i}] is {mine[i]}, the environment's "
                f"{theirs[i]}: trained on another environment or options?"
            )


def _space_json(space) -> dict:
    def bound(value):
        return "inf" if value == np.inf else "-inf" if value == -np.inf else float(value)

    low, high, names = space
    return {"low": [bound(v) for v in low], "high": [bound(v) for v in high], "names": list(names)}


def import_sb3(
    zip_path: PathLike,
    env_id: str,
    output: PathLike,
    vecnormalize: Optional[PathLike] = None,
    env_options: Optional[Dict[str, str]] = None,
) -> Path:
    """Converts an SB3 PPO zip (and its VecNormalize file) trained on ``env_id`` with
    ``env_options`` into an upkie-rl model at ``output``; returns that path. Raises
    ConversionError naming the file and the reason for anything it cannot convert."""
    zip_path, output = Path(zip_path), Path(output)
    options = {str(k): str(v) for k, v in (env_options or {}).items()}
    contents = _read_zip(zip_path)
    where = str(zip_path)
    data = _sb3_data(contents, where)
    _check_ppo(data, where)
    observation_bounds = _sb3_box(data, "observation_space", where)
    action_bounds = _sb3_box(data, "action_space", where)
    observation_space, action_space = _env_spaces(env_id, options)
    _check_against_env("observation space", observation_bounds, observation_space, where)
    _check_against_env("action space", action_bounds, action_space, where)
    observation_size, action_size = len(observation_space[0]), len(action_space[0])
    activation = _activation(data, where)
    state = _policy_state(contents, where)
    parameters, actor_hidden, critic_hidden = _flat_parameters(
        state, observation_size, action_size, where
    )
    normalization = read_vec_normalize(vecnormalize, observation_size) if vecnormalize else None
    header = _import_header(
        data, contents, zip_path, env_id, options, normalization,
        observation_space, action_space, actor_hidden, critic_hidden, activation,
    )
    _core.write_model_checkpoint(str(output), json.dumps(header),
                                 {_KEY["POLICY_PARAMETERS"]: parameters})
    return output


def _readable(data: dict) -> dict:
    """The JSON-readable hyperparameters of SB3's data (not the serialised objects)."""
    keys = ("n_envs", "n_steps", "batch_size", "n_epochs", "gamma", "gae_lambda", "ent_coef",
            "vf_coef", "max_grad_norm", "learning_rate", "normalize_advantage", "target_kl",
            "num_timesteps", "seed")
    return {key: data[key] for key in keys if key in data and not isinstance(data[key], dict)}


def _import_header(data, contents, zip_path, env_id, options, normalization, observation_space,
                   action_space, actor_hidden, critic_hidden, activation):
    hyperparameters = _readable(data)
    config = {
        "env": {"id": canonical_id(env_id), "num_envs": hyperparameters.get("n_envs", 1),
                "options": options},
        "policy": {"actor_hidden_sizes": actor_hidden, "critic_hidden_sizes": critic_hidden,
                   "activation": activation},
        "sb3": hyperparameters,
        "seed": hyperparameters.get("seed"),
    }
    if normalization:
        config["normalize"] = normalization[_NORM["CONFIG"]]
    provenance = json.loads(_core.new_provenance(_IMPORT_SOURCE))
    original = _embedded_provenance(contents)
    provenance.update({
        _PROV["IMPORTED_FROM"]: {
            _PROV["FILE"]: zip_path.name,
            _PROV["SHA256"]: hashlib.sha256(zip_path.read_bytes()).hexdigest(),
            _PROV["STABLE_BASELINES3_VERSION"]:
                contents.get("_stable_baselines3_version", b"unknown")
                .decode("utf-8", "replace").strip(),
        },
        _PROV["SEED"]:
            hyperparameters.get("seed") if hyperparameters.get("seed") is not None else "unknown",
        _PROV["TIMESTEPS"]: hyperparameters.get("num_timesteps", "unknown"),
    })
    if original:
        provenance[_PROV["ORIGINAL"]] = original
    import yaml  # type: ignore[import-untyped]  # PyYAML ships no stubs; Debian has none

    return {
        _KEY["FORMAT"]: _CHECKPOINT_FORMAT,
        _KEY["VERSION"]: _CHECKPOINT_VERSION,
        _KEY["CONFIG"]: yaml.safe_dump(config, sort_keys=False),
        _KEY["COUNTERS"]: {_KEY["NUM_TIMESTEPS"]: hyperparameters.get("num_timesteps", 0)},
        _KEY["NORMALIZATION"]: normalization,
        _KEY["POLICY"]: {_KEY["OBSERVATION_SIZE"]: len(observation_space[0]),
                         _KEY["ACTION_SIZE"]: len(action_space[0]),
                         _KEY["ACTOR_HIDDEN_SIZES"]: actor_hidden,
                         _KEY["CRITIC_HIDDEN_SIZES"]: critic_hidden,
                         _KEY["ACTIVATION"]: activation},
        _KEY["OBSERVATION_SPACE"]: _space_json(observation_space),
        _KEY["ACTION_SPACE"]: _space_json(action_space),
        _KEY["PROVENANCE"]: provenance,
    }


def _embedded_provenance(contents: Dict[str, bytes]):
    """The provenance an upkie-rl export put in the zip, if any (kept through a round trip)."""
    raw = contents.get(PROVENANCE_MEMBER)
    if raw is None:
        return None
    try:
        value = json.loads(raw)
    except (UnicodeDecodeError, ValueError, RecursionError):
        return None
    return value.get(_KEY["PROVENANCE"]) if isinstance(value, dict) else None


# ---------------------------------------------------------------------------------------
# Export


def _gym_box(space: dict):
    import gymnasium as gym

    def values(key):
        return np.array([float(v) for v in space[key]], dtype=np.float32)

    return gym.spaces.Box(low=values("low"), high=values("high"), dtype=np.float32)


def _spaces_env(observation_space, action_space):
    """A one-environment VecEnv that only carries the spaces (SB3 needs one to build PPO)."""
    import gymnasium as gym
    from stable_baselines3.common.vec_env import DummyVecEnv

    class SpacesOnly(gym.Env):
        def __init__(self):
            self.observation_space = observation_space
            self.action_space = action_space

        def reset(self, *, seed=None, options=None):
            return np.zeros(observation_space.shape, np.float32), {}

        def step(self, action):
            raise RuntimeError("an exported model's placeholder environment cannot step")

    return DummyVecEnv([SpacesOnly])


def _state_dict(parameters: np.ndarray, policy: dict) -> dict:
    """SB3's MlpPolicy state dict of upkie-rl's flat parameters (the inverse of import)."""
    import torch

    observation_size, action_size = policy[_KEY["OBSERVATION_SIZE"]], policy[_KEY["ACTION_SIZE"]]
    offset, state = 0, {}

    def take(shape):
        nonlocal offset
        size = int(np.prod(shape))
        piece = parameters[offset:offset + size].reshape(shape)
        offset += size
        return torch.from_numpy(piece.copy())

    for net, hidden, head, head_size in (
        ("policy_net", policy[_KEY["ACTOR_HIDDEN_SIZES"]], "action_net", action_size),
        ("value_net", policy[_KEY["CRITIC_HIDDEN_SIZES"]], "value_net", 1),
    ):
        size = observation_size
        for i, out in enumerate(hidden):
            state[f"mlp_extractor.{net}.{2 * i}.weight"] = take((out, size))
            state[f"mlp_extractor.{net}.{2 * i}.bias"] = take((out,))
            size = out
        state[f"{head}.weight"] = take((head_size, size))
        state[f"{head}.bias"] = take((head_size,))
    state["log_std"] = take((action_size,))
    if offset != parameters.size:
        raise ConversionError(f"{parameters.size} parameters, the policy's shape needs {offset}")
    return state


def export_sb3(model: PathLike, output: PathLike, vecnormalize: Optional[PathLike] = None) -> Path:
    """Writes the upkie-rl model ``model`` as an SB3 PPO zip at ``output`` (with the model's
    provenance in its ``upkie_rl.json`` member) and, when ``vecnormalize`` is given, its
    observation statistics as a VecNormalize file there. Raises ConversionError for a model
    that normalises observations when no ``vecnormalize`` path is given."""
    import torch
    from stable_baselines3 import PPO
    from stable_baselines3.common.vec_env import VecNormalize

    model, output = Path(model), Path(output)
    header_text, tensors = _core.read_model_checkpoint(str(model))
    header = json.loads(header_text)
    policy = header[_KEY["POLICY"]]
    normalization = header.get(_KEY["NORMALIZATION"])
    normalizes = bool(normalization and normalization[_NORM["CONFIG"]][_NORM["OBSERVATIONS"]])
    if normalizes and vecnormalize is None:
        raise ConversionError(
            f"{model}: the model normalises observations; give a VecNormalize output path "
            "(--vecnormalize) or SB3 would see raw observations"
        )
    observation_space = _gym_box(header[_KEY["OBSERVATION_SPACE"]])
    action_space = _gym_box(header[_KEY["ACTION_SPACE"]])
    torch_names = {ours: torch_name for torch_name, ours in ACTIVATIONS.items()}
    ours = policy[_KEY["ACTIVATION"]]
    if ours not in torch_names:
        raise ConversionError(f"{model}: activation {ours} has no SB3 equivalent")
    activation = getattr(torch.nn, torch_names[ours])
    venv = _spaces_env(observation_space, action_space)
    provenance = json.loads(_core.model_provenance(header_text))
    ppo = PPO(
        "MlpPolicy", venv, device="cpu",
        policy_kwargs={"net_arch": {"pi": policy[_KEY["ACTOR_HIDDEN_SIZES"]],
                                    "vf": policy[_KEY["CRITIC_HIDDEN_SIZES"]]},
                       "activation_fn": activation},
        **_sb3_hyperparameters(provenance),
    )
    ppo.policy.load_state_dict(_state_dict(tensors[_KEY["POLICY_PARAMETERS"]].ravel(), policy))
    if isinstance(provenance.get(_PROV["TIMESTEPS"]), int):
        ppo.num_timesteps = provenance[_PROV["TIMESTEPS"]]
    ppo.save(output)
    member = {_PROV["ENV_ID"]: provenance.get(_PROV["ENV_ID"]),
              _PROV["ENV_OPTIONS"]: provenance.get(_PROV["ENV_OPTIONS"]),
              _KEY["PROVENANCE"]: provenance}
    with zipfile.ZipFile(output, "a") as archive:
        archive.writestr(PROVENANCE_MEMBER, json.dumps(member, indent=2))
    if vecnormalize is not None:
        _write_vec_normalize(normalization, venv, Path(vecnormalize))
    return output


# upkie-rl's PPO settings (the "ppo" section of a training configuration) that SB3's PPO
# takes, by SB3's name.
_PPO_SETTINGS = {"n_steps": "n_steps", "batch_size": "batch_size", "n_epochs": "n_epochs",
                 "gamma": "gamma", "gae_lambda": "gae_lambda", "clip_range": "clip_range",
                 "ent_coef": "ent_coef", "vf_coef": "vf_coef", "max_grad_norm": "max_grad_norm",
                 "learning_rate_initial": "learning_rate"}


def _sb3_hyperparameters(provenance: dict) -> dict:
    """The training's hyperparameters as SB3 PPO arguments, so that the exported model says
    how it was trained: from an upkie-rl configuration's "ppo" section, or the "sb3"
    section of an imported model; none when the model does not say."""
    import yaml

    try:
        config = yaml.safe_load(provenance.get(_PROV["CONFIG"], ""))
    except yaml.YAMLError:
        return {}
    if not isinstance(config, dict):
        return {}
    if isinstance(config.get("ppo"), dict):
        settings = {sb3: config["ppo"][ours] for ours, sb3 in _PPO_SETTINGS.items()
                    if ours in config["ppo"]}
    elif isinstance(config.get("sb3"), dict):
        settings = {key: config["sb3"][key] for key in _PPO_SETTINGS.values()
                    if key in config["sb3"]}
    else:
        settings = {}
    # YAML 1.1 reads "2e-04" as text: such numbers are read back here.
    settings = {key: _typed(value) for key, value in settings.items()}
    settings = {key: value for key, value in settings.items()
                if isinstance(value, (int, float)) and not isinstance(value, bool)}
    seed = config.get("seed")
    if isinstance(seed, int) and not isinstance(seed, bool):
        settings["seed"] = seed
    return settings


def _write_vec_normalize(normalization, venv, path: Path) -> None:
    from stable_baselines3.common.vec_env import VecNormalize

    if not normalization:
        VecNormalize(venv, norm_obs=False, norm_reward=False).save(str(path))
        return
    config = normalization[_NORM["CONFIG"]]
    wrapper = VecNormalize(
        venv, norm_obs=config[_NORM["OBSERVATIONS"]], norm_reward=config[_NORM["REWARDS"]],
        clip_obs=config[_NORM["CLIP_OBSERVATIONS"]], clip_reward=config[_NORM["CLIP_REWARDS"]],
        gamma=config[_NORM["GAMMA"]], epsilon=config[_NORM["EPSILON"]],
    )
    for name, key in (("obs_rms", "OBSERVATION_STATISTICS"), ("ret_rms", "RETURN_STATISTICS")):
        statistics = normalization.get(_NORM[key])
        if statistics:
            rms = getattr(wrapper, name)
            rms.mean = np.array(statistics[_NORM["MEAN"]], dtype=np.float64).reshape(rms.mean.shape)
            rms.var = np.array(statistics[_NORM["VAR"]], dtype=np.float64).reshape(rms.var.shape)
            rms.count = float(statistics[_NORM["COUNT"]])
    wrapper.training = False
    wrapper.save(str(path))


# ---------------------------------------------------------------------------------------
# Command line


def describe_sb3(zip_path: PathLike) -> dict:
    """What an SB3 zip says of itself (read as in import, nothing executed)."""
    zip_path = Path(zip_path)
    contents = _read_zip(zip_path)
    data = _sb3_data(contents, str(zip_path))
    provenance = (_json_member(contents, PROVENANCE_MEMBER, str(zip_path))
                  if PROVENANCE_MEMBER in contents else None)
    return {
        "policy_class": _policy_class_name(data),
        "stable_baselines3_version": contents.get("_stable_baselines3_version", b"unknown")
        .decode("utf-8", "replace").strip(),
        "hyperparameters": _readable(data),
        "upkie_rl": provenance,
    }


def _options(pairs: List[str]) -> Dict[str, str]:
    options = {}
    for pair in pairs:
        key, equal, value = pair.partition("=")
        if not equal or not key:
            raise ConversionError(f"--env-option {pair!r}: expected key=value")
        options[key] = value
    return options


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python3 -m upkie_rl.sb3_convert",
        description="Convert Stable-Baselines3 PPO models to and from upkie-rl models.",
    )
    commands = parser.add_subparsers(dest="command", required=True)
    to_ckpt = commands.add_parser("import", help="SB3 PPO zip (+ VecNormalize file) -> .ckpt")
    to_ckpt.add_argument("zip", help="PPO model saved by SB3 (model.save)")
    to_ckpt.add_argument("--env", required=True, help="Environment id it was trained on")
    to_ckpt.add_argument("--env-option", action="append", default=[], metavar="KEY=VALUE",
                         help="Environment option it was trained with (repeatable)")
    to_ckpt.add_argument("--vecnormalize", help="VecNormalize statistics file (VecNormalize.save)")
    to_ckpt.add_argument("--output", "-o", required=True, help=".ckpt file to write")
    to_zip = commands.add_parser("export", help=".ckpt -> SB3 PPO zip (+ VecNormalize file)")
    to_zip.add_argument("model", help="upkie-rl model (.ckpt)")
    to_zip.add_argument("--output", "-o", required=True, help="zip file to write")
    to_zip.add_argument("--vecnormalize", help="VecNormalize file to write")
    info = commands.add_parser("info", help="Describe an SB3 zip without loading it")
    info.add_argument("zip")
    args = parser.parse_args(argv)
    try:
        if args.command == "import":
            written = import_sb3(args.zip, args.env, args.output, args.vecnormalize,
                                 _options(args.env_option))
            print(f"wrote {written}")
        elif args.command == "export":
            written = export_sb3(args.model, args.output, args.vecnormalize)
            print(f"wrote {written}" + (f" and {args.vecnormalize}" if args.vecnormalize else ""))
        else:
            print(json.dumps(describe_sb3(args.zip), indent=2))
    except (ValueError, FileNotFoundError) as error:  # ConversionError, CheckpointError, ...
        print(f"upkie_rl.sb3_convert: error: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
