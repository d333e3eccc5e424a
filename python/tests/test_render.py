"""render_mode="rgb_array": frames of the robot drawn offscreen, and Gymnasium's RecordVideo."""

import subprocess

import gymnasium as gym
import numpy as np
import pytest

import upkie_rl  # noqa: F401  (registers the ids)


def changed_fraction(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.mean(np.any(np.abs(a.astype(int) - b.astype(int)) > 24, axis=2)))


@pytest.mark.parametrize("backend", ["MuJoCo", "Bullet"])
def test_rgb_array_frames_follow_the_robot(backend):
    env = gym.make(
        f"upkie_rl/Upkie-{backend}-Pendulum", render_mode="rgb_array", render_width=320,
        render_height=240,
    )
    assert env.metadata["render_fps"] == pytest.approx(200.0)
    env.reset(seed=0)
    first = env.render()
    assert first.shape == (240, 320, 3) and first.dtype == np.uint8
    for _ in range(200):  # zero ground velocity: the robot falls within a second
        _, _, terminated, _, _ = env.step(np.zeros(1, dtype=np.float32))
        if terminated:
            break
    later = env.render()
    assert changed_fraction(first, later) > 0.01
    env.close()


def test_render_without_render_mode_warns_and_returns_none():
    env = gym.make("upkie_rl/Upkie-MuJoCo-Pendulum")
    env.reset(seed=0)
    with pytest.warns(UserWarning, match="render_mode"):
        assert env.render() is None


def test_unsupported_render_mode_is_refused():
    with pytest.raises(ValueError, match="ansi"):
        gym.make("upkie_rl/Upkie-MuJoCo-Pendulum", render_mode="ansi")


def test_render_errors_are_runtime_errors():
    from upkie_rl import _core

    assert issubclass(_core.RenderError, RuntimeError)


def test_record_video_writes_a_playable_mp4(tmp_path):
    env = gym.make(
        "upkie_rl/Upkie-MuJoCo-Pendulum", render_mode="rgb_array", render_width=160,
        render_height=120, max_episode_steps=40,
    )
    env = gym.wrappers.RecordVideo(env, str(tmp_path), episode_trigger=lambda e: True,
                                   disable_logger=True)
    env.reset(seed=0)
    done = False
    while not done:
        _, _, terminated, truncated, _ = env.step(np.zeros(1, dtype=np.float32))
        done = terminated or truncated
    env.close()
    videos = list(tmp_path.glob("*.mp4"))
    assert len(videos) == 1
    frames = subprocess.run(
        ["ffprobe", "-v", "error", "-select_streams", "v:0", "-count_frames", "-show_entries",
         "stream=nb_read_frames", "-of", "csv=p=0", str(videos[0])],
        capture_output=True, text=True, check=True,
    ).stdout.strip()
    assert int(frames) > 1


def test_rendering_works_after_importing_torch():
    """Debian's PyTorch loads libGL (through Qt); rendering must not depend on the order of
    imports (with an OSMesa context, MuJoCo then failed to load OpenGL and exited)."""
    import os
    import sys

    script = (
        "import torch, gymnasium as gym, numpy as np, upkie_rl\n"
        "env = gym.make('upkie_rl/Upkie-MuJoCo-Pendulum', render_mode='rgb_array',"
        " render_width=64, render_height=48)\n"
        "env.reset(seed=0)\n"
        "frame = env.render()\n"
        "assert frame.shape == (48, 64, 3) and frame.std() > 0, frame.shape\n"
        "print('rendered')\n"
    )
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            env=dict(os.environ), timeout=120)
    assert result.returncode == 0, result.stderr
    assert "rendered" in result.stdout
