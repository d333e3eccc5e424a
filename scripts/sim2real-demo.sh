#!/usr/bin/env bash
# `make sim2real-demo`: the loop from a robot's log back to a better policy, with a Bullet
# simulation spine playing the robot. The spine hides its physics from everything else (a
# payload, a slippery floor, late and lagging actuation); the runner records 60 s of the
# identification script on it with the nominal velocity policy; `upkie-rl identify` fits
# those options on MuJoCo from the spine's log; the velocity policy is retrained with them;
# and both policies are evaluated on the hidden reality, side by side.
#
# Usage: scripts/sim2real-demo.sh [OUTPUT_DIR]   (default runs/sim2real-demo-<date>-<time>;
# an earlier run's directory goes on where it stopped)
# Settings (environment variables, defaults in brackets): BUILD_DIR [build], NOMINAL_MODEL
# [tests/data/policies/velocity_mujoco_seed0.ckpt], RECORD_SECONDS [62], TOTAL_TIMESTEPS [the
# configuration's], EPISODES [20], SEED [1000]. Smaller values make a quick check of the
# plumbing (tests/apps/sim2real_demo_test.cpp), not a result.
set -euo pipefail

build_dir=${BUILD_DIR:-build}
out=${1:-runs/sim2real-demo-$(date +%Y%m%d-%H%M%S)}
nominal_model=${NOMINAL_MODEL:-tests/data/policies/velocity_mujoco_seed0.ckpt}
record_seconds=${RECORD_SECONDS:-62}
episodes=${EPISODES:-20}
seed=${SEED:-1000}
cli=$build_dir/upkie-rl
agent=$build_dir/upkie-rl-agent

# The hidden reality. The owner weighed the payload (1 kg) but does not know where its centre
# of mass sits, how slippery the floor is, nor how late and slow the actuation is.
hidden_physics=(--physics-option payload_mass=1 --physics-option payload_offset_x=0.04
                --physics-option floor_friction=0.6)
hidden_actuation=(--action-delay 0.02 --action-lag 0.01)
known_options=(--env-option payload_mass=1)
known_sets=(--set env.options.payload_mass=1)

mkdir -p "$out"
spine_pid=
stop_spine() {
  if [[ -n $spine_pid ]]; then
    kill -INT "$spine_pid" 2>/dev/null || true
    wait "$spine_pid" 2>/dev/null || true
    spine_pid=
  fi
}
trap stop_spine EXIT

# Starts the hidden reality's spine on shared memory $1 with the extra arguments after it,
# its output in $out/<name>.log, and waits until it serves.
start_spine() {
  local shm_name=$1
  shift
  "$cli" spine --backend bullet --shm-name "$shm_name" "${hidden_physics[@]}" \
    "${hidden_actuation[@]}" "$@" >"$out/spine${shm_name//\//_}.log" 2>&1 &
  spine_pid=$!
  for _ in $(seq 100); do
    [[ -e /dev/shm$shm_name ]] && return 0
    sleep 0.1
  done
  echo "sim2real-demo: the spine did not start; see $out/spine${shm_name//\//_}.log" >&2
  exit 1
}

# A run given the directory of an earlier one goes on where that one stopped: the robot's
# log and its fit, and a finished training, are kept (and said so), not redone.
if [[ -s $out/identify.txt ]]; then
  echo "== 1-2/4 the robot's log and its fit: kept from $out"
else
  echo "== 1/4 the robot's run: $record_seconds s of configs/identify_commands.csv on the hidden reality"
  record_shm=/upkie_sim2real_record_$$
  start_spine "$record_shm" --log "$out/robot.mpack"
  "$agent" --model "$nominal_model" --shm-name "$record_shm" \
    --commands configs/identify_commands.csv --duration "$record_seconds" \
    --record "$out/robot.csv" >"$out/agent.log" 2>&1 || {
    echo "sim2real-demo: the runner stopped early (it may have fallen); the log so far is used" >&2
  }
  stop_spine
  tail -n 1 "$out/agent.log"

  echo "== 2/4 identify on MuJoCo from the spine's log"
  "$cli" identify --log "$out/robot.mpack" --env Upkie-MuJoCo-Servos \
    --env-option frequency=50 "${known_options[@]}" \
    --param payload_offset_x=-0.1:0.1 --param floor_friction=0.2:1.5 \
    --param action_delay=0:3 --param action_lag=0:0.1 \
    --output "$out/identified.yaml" --json >"$out/identify.txt.partial"
  mv "$out/identify.txt.partial" "$out/identify.txt"
  cat "$out/identify.txt"
fi

identified_model=$(ls -t "$out"/retrained/model_*.ckpt 2>/dev/null | head -n 1 || true)
if [[ -n $identified_model ]]; then
  echo "== 3/4 the retrained policy: kept, $identified_model"
else
  echo "== 3/4 retrain the velocity policy with the identified options"
  read -r -a identified_sets <<<"$(sed -n 's/^# train://p' "$out/identified.yaml")"
  steps=()
  [[ -n ${TOTAL_TIMESTEPS:-} ]] && steps=(--set "ppo.total_timesteps=$TOTAL_TIMESTEPS")
  "$cli" train --config configs/velocity.yaml "${identified_sets[@]}" "${known_sets[@]}" \
    "${steps[@]}" --run-dir "$out/retrained" --quiet
  identified_model=$(ls -t "$out"/retrained/model_*.ckpt | head -n 1)
fi

echo "== 4/4 both policies on the hidden reality: $episodes episodes of 20 s, random commands"
evaluate() {
  local name=$1 model=$2 shm_name=/upkie_sim2real_eval_$$
  # On request (20 physics steps of 1 ms per 50 Hz agent step): the same physics, faster.
  start_spine "$shm_name" --nb-substeps 20
  "$cli" rollout --env Upkie-Spine-Velocity --model "$model" \
    --env-option "shm_name=$shm_name" --env-option regulate_frequency=false \
    --env-option request_timeout=10 \
    --env-option max_episode_steps=1000 --max-steps 1000 \
    --episodes "$episodes" --seed "$seed" --json >"$out/$name.txt" 2>&1
  stop_spine
  tail -n 1 "$out/$name.txt" >"$out/$name.json"
}
evaluate nominal "$nominal_model"
evaluate identified "$identified_model"

python3 - "$out" "$episodes" <<'EOF'
import json
import sys

out, episodes = sys.argv[1], int(sys.argv[2])
fit = json.loads(open(f"{out}/identify.txt").read().strip().splitlines()[-1])
print(f"\nhidden reality (Bullet spine): payload 1 kg (known) at x +0.04 m, floor friction 0.6,")
print("  commands 20 ms late (1 step at 50 Hz), first-order lag 0.01 s")
identified = ", ".join(
    f"{name} {value:.4g}" + ("" if fit["identifiable"][name] else " (not identifiable)")
    for name, value in fit["params"].items())
print(f"identified on MuJoCo: {identified}; rmse {fit['rmse_before']:.3f} -> "
      f"{fit['rmse_after']:.3f}, {fit['seconds']:.1f} s")
print(f"\n{'policy':<12}{'falls':>8}{'tracking_rms_vx':>18}{'tracking_rms_wz':>18}{'mean return':>14}")
rows = {}
for name in ("nominal", "identified"):
    result = json.loads(open(f"{out}/{name}.json").read())
    falls = round(result["fall_rate"] * result["episodes"])
    rows[name] = result
    print(f"{name:<12}{falls:>5}/{result['episodes']:<2}{result['tracking_rms_vx']:>18.4f}"
          f"{result['tracking_rms_wz']:>18.4f}{result['mean_return']:>14.1f}")
json.dump({"identify": fit, "nominal": rows["nominal"], "identified": rows["identified"]},
          open(f"{out}/summary.json", "w"), indent=1)
print(f"\nwrote {out}/summary.json")
EOF
