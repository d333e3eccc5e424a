#!/bin/bash
# Steps/s of the seed's pendulum trained by WORLD ranks of one DD-PPO run on this machine,
# the ranks launched with torchrun's variables (docs/training.md, "Speed on this machine").
# Usage: scripts/measure_ranks.sh WORLD [STEPS]   e.g. for w in 1 2 4; do scripts/measure_ranks.sh $w; done
set -euo pipefail
cd "$(dirname "$0")/.."
world=${1:?usage: $0 WORLD [STEPS]}
steps=${2:-204800}
out=$(mktemp -d)
port=$((30000 + RANDOM % 20000))
pids=()
for ((rank = world - 1; rank >= 0; rank--)); do
  WORLD_SIZE=$world RANK=$rank LOCAL_RANK=$rank MASTER_ADDR=127.0.0.1 MASTER_PORT=$port \
    build/upkie-rl train --config configs/pendulum.yaml --set ppo.total_timesteps="$steps" \
    --quiet --run-dir "$out/rank$rank" > "$out/rank$rank.log" 2>&1 &
  pids+=($!)
done
wait "${pids[@]}"
echo "== $world rank(s)"
grep -h "trained\|time:" "$out/rank0.log"
rm -rf "$out"
