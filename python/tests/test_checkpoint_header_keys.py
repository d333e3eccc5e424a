"""The checkpoint header's keys reach Python from their one C++ declaration
(policy/checkpoint_header.hpp): they name every entry of the trained checkpoints in
tests/data/policies (the SB3 converter, which writes and reads headers with them, is
tested in test_sb3_convert.py). So do the normalisation state's keys
(vec/normalization_state.hpp) and the provenance's (policy/provenance.hpp). The converter's
activation table comes from policy/activation.hpp's list the same way."""

import json
from pathlib import Path

from upkie_rl import _core

POLICIES = Path(__file__).resolve().parents[2] / "tests" / "data" / "policies"


def test_declared_keys_name_every_entry_of_a_trained_checkpoint():
    keys = _core.checkpoint_header_keys()
    assert keys["NUM_TIMESTEPS"] == "num_timesteps"
    assert keys["N_UPDATES"] == "n_updates"
    assert keys["POLICY_PARAMETERS"] == "policy.parameters"
    declared = set(keys.values())
    for path in sorted(POLICIES.glob("*.ckpt")):
        header_text, tensors = _core.read_model_checkpoint(str(path))
        header = json.loads(header_text)
        assert set(header) <= declared, (path.name, set(header) - declared)
        assert set(header[keys["POLICY"]]) <= declared, path.name
        assert set(header[keys["COUNTERS"]]) <= declared, path.name
        assert set(tensors) <= declared, path.name
        assert (header[keys["FORMAT"]], header[keys["VERSION"]]) == _core.checkpoint_format()



def test_declared_normalization_and_provenance_keys_name_every_entry_of_trained_checkpoints():
    keys = _core.checkpoint_header_keys()
    norm = _core.normalization_state_keys()
    assert norm["CLIP_OBSERVATIONS"] == "clip_observations"
    assert norm["OBSERVATION_STATISTICS"] == norm["OBSERVATIONS"] == "observations"
    provenance_keys = _core.provenance_keys()
    assert provenance_keys["ENV_ID"] == "env_id"
    assert provenance_keys["STABLE_BASELINES3_VERSION"] == "stable_baselines3_version"
    normalized = 0
    for path in sorted(POLICIES.glob("*.ckpt")):
        header_text, _ = _core.read_model_checkpoint(str(path))
        header = json.loads(header_text)
        state = header[keys["NORMALIZATION"]]
        if state is not None:
            normalized += 1
            assert set(state) == {norm["OBSERVATION_STATISTICS"], norm["RETURN_STATISTICS"],
                                  norm["CONFIG"]}, path.name
            assert set(state[norm["OBSERVATION_STATISTICS"]]) == {
                norm["MEAN"], norm["VAR"], norm["COUNT"]}, path.name
            assert set(state[norm["CONFIG"]]) == {
                norm[name] for name in ("OBSERVATIONS", "REWARDS", "CLIP_OBSERVATIONS",
                                        "CLIP_REWARDS", "GAMMA", "EPSILON")}, path.name
        provenance = json.loads(_core.model_provenance(header_text))
        assert set(provenance) <= set(provenance_keys.values()), path.name
        for name in ("UPKIE_RL_VERSION", "SOURCE", "ENV_ID", "SEED", "TIMESTEPS", "CONFIG"):
            assert provenance_keys[name] in provenance, (path.name, name)
    assert normalized > 0


def test_the_converter_maps_every_pytorch_activation_class_from_the_one_list():
    names = _core.activation_torch_names()
    assert names["ReLU"] == "relu"
    assert names["LeakyReLU"] == "leaky_relu"
    assert sorted(names.values()) == sorted(
        ["relu", "tanh", "elu", "leaky_relu", "silu", "gelu", "sigmoid", "softplus", "selu"])
