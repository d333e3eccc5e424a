#!/usr/bin/env bash
# Loop timing of the same policy against the real-time `upkie-rl spine`, run by the robot
# runner (`upkie-rl-agent`) and by the full binary (`upkie-rl rollout --model` on
# Upkie-Spine-Pendulum), measured the same way for both: the period between successive
# observations by the spine's clock (the `t` column of their record files, 1 ms steps), and
# for the runner also its own loop_period column. Usage:
#   scripts/measure_loop_timing.sh [BUILD_DIR] [MODEL] [SECONDS]
# Prints one table row per runner; a deadline miss is a period above 1.5 task periods.
set -euo pipefail
build=${1:-build}
model=${2:-tests/data/policies/pendulum_bullet_seed0.ckpt}
seconds=${3:-10}
work=$(mktemp -d)
shm=/upkie_rl_timing_$$
"$build/upkie-rl" spine --shm-name "$shm" >"$work/spine.log" 2>&1 &
spine=$!
trap 'kill -INT $spine 2>/dev/null; wait $spine 2>/dev/null; rm -rf "$work"' EXIT
for _ in $(seq 100); do [ -e "/dev/shm$shm" ] && break; sleep 0.05; done
"$build/upkie-rl-agent" --model "$model" --shm-name "$shm" --duration "$seconds" \
  --record "$work/agent.csv" >"$work/agent.log" 2>&1 || { cat "$work/agent.log"; exit 1; }
steps=$(python3 -c "print(int($seconds * 200))")
"$build/upkie-rl" rollout --env Upkie-Spine-Pendulum --model "$model" \
  --env-option shm_name="$shm" --env-option max_episode_steps="$steps" --max-steps "$steps" \
  --record "$work/rollout.csv" >"$work/rollout.log" 2>&1 || { cat "$work/rollout.log"; exit 1; }
python3 - "$work/agent.csv" "$work/rollout.csv" <<'PYTHON'
import csv
import sys

def stats(name, periods, period=0.005):
    periods = sorted(periods)
    mean = sum(periods) / len(periods)
    p99 = periods[min(len(periods) - 1, int(0.99 * len(periods)))]
    misses = sum(1 for value in periods if value > 1.5 * period)
    print(f"| {name} | {len(periods) + 1} | {mean * 1e3:.3f} ms | {p99 * 1e3:.3f} ms | "
          f"{periods[-1] * 1e3:.3f} ms | {misses} |")

print("| loop | cycles | period mean | p99 | max | deadline misses |")
print("| --- | --- | --- | --- | --- | --- |")
for label, path in (("upkie-rl-agent", sys.argv[1]), ("upkie-rl rollout", sys.argv[2])):
    rows = list(csv.DictReader(open(path)))
    times = [float(row["t"]) for row in rows]
    stats(label + ", spine clock", [b - a for a, b in zip(times, times[1:])])
    if "loop_period" in rows[0]:
        stats(label + ", own clock", [float(row["loop_period"]) for row in rows[1:]])
PYTHON
