// Every option a settings struct declares reaches the registry's listing (`envs --options`,
// Python's option table) and is read back by the registry: no option declared on one side
// only.

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "envs/registry/env_settings.hpp"
#include "envs/registry/registry.hpp"

namespace upkie_rl {
namespace {

std::vector<std::string> names_of(const std::function<void(OptionTable&)>& declare) {
  OptionTable table;
  declare(table);
  return table.names();
}

// The options each settings struct declares for `id`, and whether they are randomisation.
std::vector<std::pair<std::string, bool>> declared_options(const EnvId& id) {
  EnvSettings s;
  std::vector<std::pair<std::vector<std::string>, bool>> groups;
  groups.push_back({names_of([&](OptionTable& t) { s.init_rand.declare_options(t); }), true});
  groups.push_back({names_of([&](OptionTable& t) { s.action_lag.declare_options(t); }), true});
  if (id.backend == EnvBackend::kSpine) {
    groups.push_back({names_of([&](OptionTable& t) { s.spine.declare_options(t); }), false});
  } else if (id.backend != EnvBackend::kMock) {
    groups.push_back({names_of([&](OptionTable& t) { s.perturbations.declare_options(t); }), true});
    groups.push_back({names_of([&](OptionTable& t) { s.bumps.declare_options(t); }), true});
  }
  switch (id.kind) {
    case EnvKind::kPendulum:
      groups.push_back({names_of([&](OptionTable& t) { s.pendulum.declare_options(t); }), false});
      break;
    case EnvKind::kGyropod:
      groups.push_back({names_of([&](OptionTable& t) { s.gyropod.declare_options(t); }), false});
      break;
    case EnvKind::kServosTask:
      groups.push_back({names_of([&](OptionTable& t) { s.task.declare_options(t); }), false});
      break;
    case EnvKind::kVelocity:
      groups.push_back({names_of([&](OptionTable& t) { s.commands.declare_options(t); }), false});
      groups.push_back({names_of([&](OptionTable& t) { s.velocity.declare_options(t); }), false});
      break;
    case EnvKind::kServos:
      break;
  }
  std::vector<std::pair<std::string, bool>> options;
  for (const auto& [names, randomization] : groups) {
    for (const std::string& name : names) options.emplace_back(name, randomization);
  }
  return options;
}

TEST(EnvOptionDeclarations, EveryDeclaredOptionIsListedTypedAndRead) {
  for (const std::string& id_name : registered_env_ids()) {
    const EnvId id = parse_env_id(id_name);
    const std::vector<OptionInfo> info = env_option_info(id_name);
    const std::vector<std::string> help = env_option_help(id_name);
    ASSERT_EQ(info.size(), help.size()) << id_name;
    std::set<std::string> listed;
    for (std::size_t i = 0; i < info.size(); ++i) {
      EXPECT_EQ(help[i].rfind(info[i].name + ": ", 0), 0u) << id_name << ": " << help[i];
      EXPECT_TRUE(listed.insert(info[i].name).second) << id_name << " lists twice " << info[i].name;
    }
    for (const auto& [name, randomization] : declared_options(id)) {
      const auto found = std::find_if(
          info.begin(), info.end(), [&](const OptionInfo& option) { return option.name == name; });
      ASSERT_NE(found, info.end()) << id_name << " does not list " << name;
      EXPECT_EQ(found->randomization, randomization) << id_name << ": " << name;
    }
    // Every listed default reads back through the registry (non-empty texts only: an empty
    // text option, such as base_controller, means "none" and is not given).
    EnvOptions defaults;
    for (const OptionInfo& option : info) {
      if (!option.default_value.empty()) defaults.emplace_back(option.name, option.default_value);
    }
    EXPECT_NO_THROW(parse_env_settings(id, id_name, defaults)) << id_name;
  }
}

TEST(EnvOptionDeclarations, SharedNamesMeanTheSameEverywhere) {
  // fall_pitch, max_ground_velocity and leg_gain_scale are declared once (shared_options.hpp)
  // and used by several kinds: the same help and bounds wherever they appear.
  for (const char* name : {"fall_pitch", "max_ground_velocity", "leg_gain_scale"}) {
    std::vector<OptionInfo> seen;
    for (const std::string& id : registered_env_ids()) {
      for (const OptionInfo& option : env_option_info(id)) {
        if (option.name == name) seen.push_back(option);
      }
    }
    ASSERT_GE(seen.size(), 2u) << name;
    for (const OptionInfo& option : seen) {
      EXPECT_EQ(option.help, seen.front().help) << name;
      EXPECT_EQ(option.min, seen.front().min) << name;
      EXPECT_EQ(option.max, seen.front().max) << name;
    }
  }
}

TEST(EnvOptionDeclarations, SettingsRulesAreCheckedByTheRegistry) {
  const EnvId id = parse_env_id("Upkie-Bullet-Velocity");
  EXPECT_THROW(parse_env_settings(id, "v", {{"push_force", "5"}, {"push_force_min", "6"}}),
               std::invalid_argument);
  EXPECT_THROW(parse_env_settings(id, "v", {{"action_lag_min", "0.2"}, {"action_lag_max", "0.1"}}),
               std::invalid_argument);
  EXPECT_THROW(
      parse_env_settings(id, "v",
                         {{"command_resample_time_min", "3"}, {"command_resample_time_max", "2"}}),
      std::invalid_argument);
}

// The spine's link refuses observations without the IMU's acceleration exactly when the
// velocity task observes it (SpineBackendConfig::require_imu_acceleration).
TEST(EnvOptionDeclarations, TheSpineRequiresTheAccelerationTheTaskObserves) {
  const EnvId id = parse_env_id("Upkie-Spine-Velocity");
  EXPECT_FALSE(spine_backend_config(parse_env_settings(id, "v", {})).require_imu_acceleration);
  const EnvSettings observing = parse_env_settings(id, "v", {{"observe_acceleration", "true"}});
  EXPECT_TRUE(spine_backend_config(observing).require_imu_acceleration);
  EXPECT_FALSE(
      spine_backend_config(parse_env_settings(parse_env_id("Upkie-Spine-Pendulum"), "p", {}))
          .require_imu_acceleration);
}

}  // namespace
}  // namespace upkie_rl
