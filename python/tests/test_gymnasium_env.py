"""upkie_rl single environments as Gymnasium environments (gym.make, spaces, options, info,
seeding, bad input), checked by Gymnasium's and SB3's own checkers."""

import warnings

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import upkie_rl

LOCAL_IDS = [
    env_id for env_id in upkie_rl.registered_env_ids() if "-Spine-" not in env_id
]
SERVO_JOINTS = {"left_hip", "left_knee", "left_wheel", "right_hip", "right_knee", "right_wheel"}


GAINS = np.array([10.0, 1.0, 0.0, 0.1], dtype=np.float32)


def pd_action(observation):
    """The CLI's `linear:10,1,0,0.1` controller, in the same float32 operations."""
    velocity = np.float32(0.0)
    for gain, value in zip(GAINS, observation):
        velocity = np.float32(velocity + np.float32(gain * value))
    return np.clip(np.array([velocity], dtype=np.float32), -1.0, 1.0)


def sb3_check_env(env):
    """SB3's checker where SB3 imports; Gymnasium's checker runs everywhere."""
    try:
        from stable_baselines3.common.env_checker import check_env as checker
    except ImportError:
        return
    checker(env)


@pytest.mark.parametrize("env_id", LOCAL_IDS)
def test_gymnasium_and_sb3_checkers_pass(env_id):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # infinite bounds, non-normalised Boxes
        check_env(gym.make(f"upkie_rl/{env_id}").unwrapped, skip_render_check=True)
        sb3_check_env(gym.make(f"upkie_rl/{env_id}"))


def test_ids_do_not_clash_with_the_public_upkie_package():
    import upkie.envs

    upkie.envs.register()
    for env_id in upkie_rl.registered_env_ids():
        assert f"upkie_rl/{env_id}" in gym.registry
    # The bare Mock and Spine ids stay the public package's.
    assert gym.spec("Upkie-Mock-Pendulum").entry_point.startswith("upkie.")
    assert gym.spec("upkie_rl/Upkie-Mock-Pendulum").entry_point == "upkie_rl.env:UpkieEnv"
    # Bullet ids, which the public package does not have, are also registered bare.
    assert gym.spec("Upkie-Bullet-Pendulum").kwargs == {"env_id": "Upkie-Bullet-Pendulum"}
    ours = gym.make("upkie_rl/Upkie-Mock-Pendulum")
    theirs = gym.make("Upkie-Mock-Pendulum")
    assert isinstance(ours.unwrapped, upkie_rl.UpkieEnv)
    assert not isinstance(theirs.unwrapped, upkie_rl.UpkieEnv)


def test_pendulum_spaces_types_and_seed_result():
    env = gym.make("Upkie-Bullet-Pendulum")
    assert env.spec.max_episode_steps == 300
    assert env.observation_space.dtype == np.float32
    assert env.observation_space.shape == (4,)
    assert env.action_space.low[0] == -1.0 and env.action_space.high[0] == 1.0
    observation, info = env.reset(seed=0)
    assert observation.dtype == np.float32
    total, steps = 0.0, 0
    while True:
        observation, reward, terminated, truncated, info = env.step(pd_action(observation))
        assert type(reward) is float
        assert terminated is False or terminated is True
        assert truncated is False or truncated is True
        total += reward
        steps += 1
        if terminated or truncated:
            break
    # The CLI's `rollout --controller linear:10,1,0,0.1` gives 295.908 over 300 steps.
    assert steps == 300 and truncated and not terminated
    assert total == pytest.approx(295.908, abs=1e-3)
    spine = info["spine_observation"]
    assert set(spine["servo"]) == SERVO_JOINTS
    assert spine["base_orientation"]["pitch"] == pytest.approx(float(observation[0]), abs=1e-6)
    assert spine["wheel_odometry"]["velocity"] == pytest.approx(float(observation[3]), abs=1e-6)
    assert len(spine["base_orientation"]["rotation_base_to_world"]) == 9
    assert isinstance(spine["floor_contact"]["contact"], bool)


def _leaf_paths(tree, prefix=""):
    paths = set()
    for key, value in tree.items():
        if isinstance(value, dict):
            paths |= _leaf_paths(value, prefix + key + ".")
        else:
            paths.add(prefix + key)
    return paths


def test_spine_observation_has_exactly_the_declared_keys():
    # The dictionary and the C++ declaration (sim/observation_fields.hpp) the spine's writer
    # and reader walk: a key added there reaches Python, and no key comes from elsewhere.
    env = gym.make("Upkie-Bullet-Pendulum")
    _, info = env.reset(seed=0)
    declared = set(upkie_rl._core.observation_keys())
    assert "base_orientation.rotation_base_to_world" in declared
    assert _leaf_paths(info["spine_observation"]) == declared
    env.close()


def test_info_can_be_left_out():
    env = gym.make("Upkie-Bullet-Pendulum", spine_observation=False)
    _, info = env.reset(seed=0)
    assert info == {}
    assert env.step(np.zeros(1, dtype=np.float32))[-1] == {}


def test_zero_action_falls_as_the_cli_says():
    env = gym.make("Upkie-Bullet-Pendulum")
    env.reset(seed=0)
    total, steps, terminated = 0.0, 0, False
    while not terminated:
        _, reward, terminated, truncated, _ = env.step(np.zeros(1, dtype=np.float32))
        total += reward
        steps += 1
        assert not truncated
    assert steps == 216  # `upkie-rl rollout --controller zero`: -61.2293 in 216 steps
    assert total == pytest.approx(-61.2293, abs=1e-3)


def test_options_are_typed_keyword_arguments():
    env = gym.make("Upkie-Bullet-Pendulum", frequency=100.0, fall_pitch=0.5)
    assert env.unwrapped.dt == pytest.approx(0.01)
    env.reset(seed=0)
    steps, terminated = 0, False
    while not terminated:
        _, _, terminated, _, info = env.step(np.zeros(1, dtype=np.float32))
        steps += 1
    assert abs(info["spine_observation"]["base_orientation"]["pitch"]) > 0.5
    assert steps < 108  # falls past 0.5 rad before 216 steps at 200 Hz (1.08 s)


def test_bad_options_name_the_problem():
    with pytest.raises(ValueError, match='unknown option "fall_pich".*fall_pitch'):
        gym.make("Upkie-Bullet-Pendulum", fall_pich=0.5)
    with pytest.raises(TypeError, match="frequency expects a real number, got str"):
        gym.make("Upkie-Bullet-Pendulum", frequency="fast")
    with pytest.raises(TypeError, match="nb_substeps expects an integer"):
        gym.make("Upkie-Bullet-Pendulum", nb_substeps=2.5)
    with pytest.raises(ValueError, match="option frequency: -1.0 is outside"):
        gym.make("Upkie-Bullet-Pendulum", frequency=-1.0)
    with pytest.raises(TypeError, match="inertia expects one of"):
        gym.make("Upkie-Bullet-Pendulum", inertia=1)
    with pytest.raises(gym.error.Error):
        gym.make("upkie_rl/Upkie-Bullet-Pendlum")


def test_bad_actions_raise_clear_python_exceptions():
    env = gym.make("Upkie-Bullet-Pendulum", disable_env_checker=True)
    env.reset(seed=0)
    with pytest.raises(ValueError, match=r"action has shape \(2,\), expected \(1,\)"):
        env.step(np.zeros(2, dtype=np.float32))
    with pytest.raises(ValueError, match="ground_velocity"):
        env.step(np.array([np.nan], dtype=np.float32))
    with pytest.raises(ValueError, match="ground_velocity"):
        env.step(np.array([np.inf]))
    with pytest.raises(TypeError, match="real numbers"):
        env.step(np.array(["fast"]))
    with pytest.raises(TypeError, match="real numbers"):
        env.step(np.array([object()], dtype=object))
    # The interpreter and the environment survive: a good action still steps.
    observation, *_ = env.step(np.array([0.0]))  # float64 is accepted and converted
    assert observation.shape == (4,)
    huge = env.step(np.array([1111.1], dtype=np.float32))[-1]["spine_observation"]
    wheel = huge["servo"]["left_wheel"]["velocity"]
    assert abs(wheel) * 0.05 <= 1.0 + 0.2  # clamped to a_max, as upkie's test asserts


def test_servos_env_takes_and_gives_upkies_nested_dicts():
    env = gym.make("Upkie-Bullet-Servos")
    observation, _ = env.reset(seed=0)
    assert set(observation) == SERVO_JOINTS
    for joint in SERVO_JOINTS:
        assert set(observation[joint]) == {"position", "velocity", "torque", "temperature",
                                           "voltage"}
        assert observation[joint]["position"].shape == (1,)
        assert observation[joint]["position"].dtype == np.float32
    assert set(env.action_space.spaces) == SERVO_JOINTS
    assert set(env.action_space["left_hip"].spaces) == {
        "position", "velocity", "feedforward_torque", "kp_scale", "kd_scale", "maximum_torque"}
    # A partial action: missing joints and keys take their neutral value.
    action = {"left_wheel": {"velocity": 5.0}, "right_wheel": {"velocity": np.array([-5.0])}}
    for _ in range(40):
        observation, reward, terminated, truncated, info = env.step(action)
    assert reward == 0.0 and not terminated and not truncated
    assert observation["left_wheel"]["velocity"][0] > 1.0
    assert info["spine_observation"]["servo"]["left_wheel"]["velocity"] > 1.0
    with pytest.raises(KeyError, match="unknown joint 'left_elbow'"):
        env.step({"left_elbow": {"position": 0.0}})
    with pytest.raises(KeyError, match="left_hip.torque"):
        env.step({"left_hip": {"torque": 0.0}})
    with pytest.raises(ValueError, match="left_hip.velocity"):
        env.step({"left_hip": {"velocity": float("nan")}})
    neutral = env.unwrapped.neutral_action()
    assert np.isnan(neutral["left_hip"]["position"][0])


def test_seeding_and_determinism():
    def trajectory(seed):
        env = gym.make("Upkie-Bullet-Pendulum", init_rand_pitch=0.1)
        observation, _ = env.reset(seed=seed)
        observations = [observation]
        for _ in range(50):
            observation, *_ = env.step(pd_action(observation))
            observations.append(observation)
        return np.array(observations)

    first, again, other = trajectory(3), trajectory(3), trajectory(4)
    np.testing.assert_array_equal(first, again)  # bit for bit
    assert not np.array_equal(first[0], other[0])  # another seed, another initial pitch
    env = gym.make("Upkie-Bullet-Pendulum", init_rand_pitch=0.1)
    a, _ = env.reset(seed=5)
    b, _ = env.reset()  # unseeded: the generator continues
    c, _ = env.reset(seed=5)
    assert not np.array_equal(a, b)
    np.testing.assert_array_equal(a, c)


def test_close_twice_and_use_after_close():
    env = gym.make("Upkie-Bullet-Pendulum")
    env.reset(seed=0)
    env.close()
    env.close()
    with pytest.raises(RuntimeError, match="closed"):
        env.unwrapped.step(np.zeros(1, dtype=np.float32))


def test_spine_id_passes_the_checkers_against_upkie_rl_spine():
    from spine_process import SpineProcess, cli_path

    if not cli_path().exists():
        pytest.fail(f"{cli_path()} not built")
    spine = SpineProcess("--nb-substeps", "5")
    try:
        options = dict(shm_name=spine.shm_name, regulate_frequency=False)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            check_env(gym.make("upkie_rl/Upkie-Spine-Pendulum", **options).unwrapped,
                      skip_render_check=True)
            sb3_check_env(gym.make("upkie_rl/Upkie-Spine-Pendulum", **options))
        env = gym.make("upkie_rl/Upkie-Spine-Pendulum", **options)
        observation, info = env.reset(seed=0)
        for _ in range(200):
            observation, _, terminated, _, info = env.step(pd_action(observation))
            assert not terminated
        assert info["spine_observation"]["time"] == pytest.approx(1.0, abs=1e-9)
        env.close()
    finally:
        assert spine.stop() == 0
