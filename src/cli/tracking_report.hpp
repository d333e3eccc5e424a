#pragma once
/// @file
/// The tracking figures of velocity tasks in the outputs of rollout and evaluate: one place
/// for their keys and wording.

#include <nlohmann/json.hpp>
#include <string>

#include "envs/evaluation/episode_runner.hpp"

namespace upkie_rl::apps {

/// Adds `tracking_rms_vx` [m/s], `tracking_rms_wz` [rad/s] (against the followed, ramped
/// command), `tracking_rms_vx_target`, `tracking_rms_wz_target` (against the targets it
/// ramped toward), `tracking_rms_height` and `tracking_rms_height_target` [m] (null without
/// a height command) and `fall_rate` to `json` when `summary` is of a velocity task (null
/// for an RMS without any step up).
void add_tracking_json(nlohmann::json& json, const EpisodeSummary& summary);

/// "tracking_rms_vx 0.081 m/s, tracking_rms_wz 0.12 rad/s, [tracking_rms_height 0.01 m, ]
/// fall_rate 0 (n steps up); against the targets tracking_rms_vx_target 0.2 m/s,
/// tracking_rms_wz_target 0.12 rad/s[, tracking_rms_height_target 0.02 m]",
/// or "" when `summary` is not of a velocity task.
std::string tracking_text(const EpisodeSummary& summary);

}  // namespace upkie_rl::apps
