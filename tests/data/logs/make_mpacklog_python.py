"""Writes mpacklog_python.mpack with the `mpacklog` package (PyPI): three cycles of a
spine log as Upkie's Python tools write them (Python ints and floats, a `spine` entry the
reader skips). tests/identify/spine_log_test.cpp reads it back."""

import mpacklog

JOINTS = ["left_hip", "left_knee", "left_wheel", "right_hip", "right_knee", "right_wheel"]

logger = mpacklog.SyncLogger("mpacklog_python.mpack")
for i in range(3):
    time = 0.005 * i
    servo = {
        joint: {
            "position": 0.1 * k,
            "velocity": 2.0 if joint == "left_wheel" and i == 2 else 0.0,
            "torque": 0,
        }
        for k, joint in enumerate(JOINTS)
    }
    observation = {
        "servo": servo,
        "base_orientation": {"angular_velocity": [0.0, 0.1, 0.0], "pitch": 0.05 if i == 1 else 0.0},
        "wheel_odometry": {"position": 0.0, "velocity": 0.0},
        "time": time,
    }
    action = {
        "servo": {
            joint: {
                "position": float("nan"),
                "velocity": -3.0 if joint == "right_wheel" else 0.0,
                "feedforward_torque": 0.0,
                "kp_scale": 1.0,
                "kd_scale": 1.0,
                "maximum_torque": 1.0,
            }
            for joint in JOINTS
        }
    }
    logger.put({"action": action, "observation": observation, "spine": {"rx_count": 6}, "time": time})
logger.write()
