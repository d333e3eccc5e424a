"""Vector environments render: gym.make_vec(..., render_mode="rgb_array") gives one frame per
sub-environment (or the first k), which Gymnasium's vector RecordVideo (1.1+) and SB3's
VecVideoRecorder write to videos."""

import subprocess

import gymnasium as gym
import numpy as np
import pytest

import upkie_rl

ENV_ID = "Upkie-MuJoCo-Pendulum"
SIZE = dict(render_width=96, render_height=64)


def video_frames(path) -> int:
    output = subprocess.run(
        ["ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
         "stream=nb_read_frames,width,height", "-of", "csv=p=0", str(path)],
        capture_output=True, text=True, check=True).stdout.strip()
    width, height, frames = (int(value) for value in output.split(","))
    return frames, width, height


def test_make_vec_renders_every_sub_env():
    venv = gym.make_vec(ENV_ID, num_envs=3, vectorization_mode="vector_entry_point",
                        render_mode="rgb_array", init_rand_pitch=0.3, **SIZE)
    assert venv.render_mode == "rgb_array"
    assert venv.metadata["render_fps"] == pytest.approx(200.0)
    venv.reset(seed=0)
    frames = venv.render()
    assert isinstance(frames, tuple) and len(frames) == 3
    for frame in frames:
        assert frame.shape == (64, 96, 3) and frame.dtype == np.uint8
    # Different initial pitches: different pictures.
    assert np.any(frames[0] != frames[1]) and np.any(frames[1] != frames[2])
    venv.close()


def test_render_envs_draws_the_first_k_only():
    venv = upkie_rl.make_vec(ENV_ID, 3, render_mode="rgb_array", render_envs=1, **SIZE)
    venv.reset(seed=0)
    frames = venv.render()
    assert len(frames) == 3 and frames[0].shape == (64, 96, 3)
    assert frames[1] is None and frames[2] is None
    with pytest.raises(ValueError, match="render_envs"):
        upkie_rl.make_vec(ENV_ID, 3, render_mode="rgb_array", render_envs=0)
    with pytest.raises(ValueError, match="human"):
        upkie_rl.make_vec(ENV_ID, 3, render_mode="human")


def test_render_without_render_mode_warns():
    venv = upkie_rl.make_vec(ENV_ID, 2)
    venv.reset(seed=0)
    with pytest.warns(UserWarning, match="render_mode"):
        assert venv.render() is None


def test_gymnasium_vector_record_video_writes_a_video(tmp_path):
    record_video = getattr(gym.wrappers.vector, "RecordVideo", None)
    if record_video is None:
        pytest.skip(f"Gymnasium {gym.__version__} has no vector RecordVideo (1.1+)")
    pytest.importorskip("moviepy")
    venv = gym.make_vec(ENV_ID, num_envs=2, vectorization_mode="vector_entry_point",
                        render_mode="rgb_array", max_episode_steps=20, **SIZE)
    venv = record_video(venv, str(tmp_path), episode_trigger=lambda episode: episode == 0)
    venv.reset(seed=0)
    for _ in range(25):
        venv.step(np.zeros((2, 1), dtype=np.float32))
    venv.close()
    (video,) = tmp_path.glob("*.mp4")
    frames, width, height = video_frames(video)
    assert frames >= 20 and (width, height) == (2 * 96, 64)  # the two sub-envs side by side


def test_sb3_vec_video_recorder_writes_a_video(tmp_path):
    pytest.importorskip("stable_baselines3")
    pytest.importorskip("moviepy")
    from stable_baselines3.common.vec_env import VecVideoRecorder

    venv = upkie_rl.make_sb3_vec_env(ENV_ID, 4, render_mode="rgb_array", render_envs=2, **SIZE)
    assert venv.render_mode == "rgb_array"
    venv = VecVideoRecorder(venv, str(tmp_path), record_video_trigger=lambda step: step == 0,
                            video_length=30, name_prefix="sb3")
    venv.reset()
    for _ in range(35):
        venv.step(np.zeros((4, 1), dtype=np.float32))
    venv.close()
    (video,) = tmp_path.glob("sb3*.mp4")
    frames, width, height = video_frames(video)
    assert frames >= 30 and (width, height) == (96, 2 * 64)  # SB3 tiles the two frames
