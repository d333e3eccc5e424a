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


def overlay_box(with_overlay: np.ndarray, without: np.ndarray):
    """Rows and columns (as fractions of the frame) where the caption changed pixels."""
    changed = np.any(with_overlay != without, axis=2)
    rows, columns = np.nonzero(changed)
    if rows.size == 0:
        return None
    height, width = changed.shape
    return (rows.max() + 1) / height, (columns.max() + 1) / width


def frames_with_and_without_overlay(width: int, height: int):
    clean = gym.make("upkie_rl/Upkie-MuJoCo-Pendulum", render_mode="rgb_array",
                     render_width=width, render_height=height)
    captioned = gym.make("upkie_rl/Upkie-MuJoCo-Pendulum", render_mode="rgb_array",
                         render_width=width, render_height=height, render_overlay=True)
    clean.reset(seed=0)
    captioned.reset(seed=0)
    return captioned.render(), clean.render()


def test_frames_are_clean_unless_the_overlay_is_asked_for():
    captioned, clean = frames_with_and_without_overlay(320, 240)
    box = overlay_box(captioned, clean)
    assert box is not None, "render_overlay=True writes a caption"
    # The caption is in the top left corner; the rest of the frame is the same picture.
    assert box[0] < 0.5 and box[1] < 0.6, box
    np.testing.assert_array_equal(captioned[150:], clean[150:])
    # The clean frame has no caption text: no white pixel in that corner (the scene has none).
    corner = clean[: int(box[0] * 240) + 1, : int(box[1] * 320) + 1]
    assert not np.any(np.all(corner > 235, axis=2))
    assert np.any(np.all(captioned[: int(box[0] * 240) + 1] > 235, axis=2))


def test_the_overlay_scales_with_the_frame():
    small = overlay_box(*frames_with_and_without_overlay(640, 480))
    large = overlay_box(*frames_with_and_without_overlay(1280, 960))
    # About the same share of the frame at both sizes (the fixed font took half as much at
    # 1280 x 960). Below 480 rows MuJoCo's smallest font keeps the caption about 52 rows tall.
    assert 0.6 < large[0] / small[0] < 1.6, (small, large)
    assert 0.6 < large[1] / small[1] < 1.6, (small, large)
