#include "cli/tracking_report.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace upkie_rl::apps {

namespace {

constexpr const char* kForwardKey = "tracking_rms_vx";
constexpr const char* kYawKey = "tracking_rms_wz";
constexpr const char* kForwardTargetKey = "tracking_rms_vx_target";
constexpr const char* kYawTargetKey = "tracking_rms_wz_target";
constexpr const char* kHeightKey = "tracking_rms_height";
constexpr const char* kHeightTargetKey = "tracking_rms_height_target";
constexpr const char* kFallRateKey = "fall_rate";

nlohmann::json number_or_null(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

}  // namespace

void add_tracking_json(nlohmann::json& json, const EpisodeSummary& summary) {
  if (!summary.has_tracking) return;
  json[kForwardKey] = number_or_null(summary.tracking.rms_forward());
  json[kYawKey] = number_or_null(summary.tracking.rms_yaw());
  json[kForwardTargetKey] = number_or_null(summary.tracking.rms_forward_target());
  json[kYawTargetKey] = number_or_null(summary.tracking.rms_yaw_target());
  json[kHeightKey] = number_or_null(summary.tracking.rms_height());
  json[kHeightTargetKey] = number_or_null(summary.tracking.rms_height_target());
  json[kFallRateKey] = summary.fall_rate;
}

std::string tracking_text(const EpisodeSummary& summary) {
  if (!summary.has_tracking) return "";
  std::ostringstream text;
  text << std::setprecision(3) << kForwardKey << ' ' << summary.tracking.rms_forward() << " m/s, "
       << kYawKey << ' ' << summary.tracking.rms_yaw() << " rad/s, ";
  if (summary.tracking.height_command) {
    text << kHeightKey << ' ' << summary.tracking.rms_height() << " m, ";
  }
  text << kFallRateKey << ' ' << summary.fall_rate << " (" << summary.tracking.steps
       << " steps up); against the targets " << kForwardTargetKey << ' '
       << summary.tracking.rms_forward_target() << " m/s, " << kYawTargetKey << ' '
       << summary.tracking.rms_yaw_target() << " rad/s";
  if (summary.tracking.height_command) {
    text << ", " << kHeightTargetKey << ' ' << summary.tracking.rms_height_target() << " m";
  }
  return text.str();
}

}  // namespace upkie_rl::apps
