#!/bin/sh
# Runs the policy of this bundle on the robot: the spine must be running (Upkie's pi3hat
# spine). Extra arguments go to upkie-rl-agent (--duration, --record, --dry-run, limits).
# The runner is pinned to CPU 3, as Upkie's agents are (the spine uses CPUs 1 and 2).
here="$(cd "$(dirname "$0")" && pwd)"
export UPKIE_RL_MODEL="$here/upkie.urdf"
if command -v taskset >/dev/null 2>&1 && [ "$(nproc)" -ge 4 ]; then pin="taskset -c 3"; else pin=""; fi
exec $pin "$here/upkie-rl-agent" --model "$here/policy.ckpt" "$@"
