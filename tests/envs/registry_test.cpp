#include "envs/registry/registry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "common/error_message.hpp"
#include "envs/kinds/servos_env.hpp"
#include "envs/registry/env_factory.hpp"

namespace upkie_rl {
namespace {

using testing::error_message;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Registry, ListsEveryKindForEachBackend) {
  const std::vector<std::string> ids = registered_env_ids();
  for (const char* id :
       {"Upkie-Mock-Servos", "Upkie-Mock-Pendulum", "Upkie-Mock-Gyropod", "Upkie-Mock-ServosTask",
        "Upkie-Bullet-Servos", "Upkie-Bullet-Pendulum", "Upkie-Bullet-Gyropod",
        "Upkie-Bullet-ServosTask", "Upkie-MuJoCo-Servos", "Upkie-MuJoCo-Pendulum",
        "Upkie-MuJoCo-Gyropod", "Upkie-MuJoCo-ServosTask", "Upkie-Spine-Servos",
        "Upkie-Spine-Pendulum", "Upkie-Spine-Gyropod", "Upkie-Spine-ServosTask"}) {
    EXPECT_NE(std::find(ids.begin(), ids.end(), id), ids.end()) << id;
  }
}

TEST(Registry, UnknownIdIsNotFoundAndListsTheKnownIds) {
  const std::string message = error_message([] { make_env("Upkie-Mock-Walker"); });
  EXPECT_TRUE(contains(message, "\"Upkie-Mock-Walker\" not found")) << message;
  EXPECT_TRUE(contains(message, "Upkie-Mock-Pendulum")) << message;
  EXPECT_FALSE(error_message([] { make_env("Pendulum"); }).empty());
  EXPECT_FALSE(error_message([] { make_env("Upkie-Mock-"); }).empty());
}

TEST(Registry, PyBulletIsAnAliasOfBullet) {
  auto env = make_env("Upkie-PyBullet-Pendulum");
  EXPECT_EQ(env->observation_space().size(), 4u);
  EXPECT_EQ(env->physics_steps_per_step(), 5);
}

TEST(Registry, UnknownOptionListsTheValidOnes) {
  const std::string message = error_message([] {
    make_env("Upkie-Mock-Pendulum", {{"max_ground_speed", "2"}});
  });
  EXPECT_TRUE(contains(message, "unknown option \"max_ground_speed\"")) << message;
  EXPECT_TRUE(contains(message, "max_ground_velocity")) << message;
  EXPECT_TRUE(contains(message, "fall_pitch")) << message;
  // Servos has no pendulum options.
  EXPECT_FALSE(error_message([] { make_env("Upkie-Mock-Servos", {{"fall_pitch", "1"}}); }).empty());
}

TEST(Registry, BadlyTypedValuesAreNamed) {
  const std::string message = error_message([] {
    make_env("Upkie-Mock-Pendulum", {{"fall_pitch", "abc"}});
  });
  EXPECT_TRUE(contains(message, "fall_pitch")) << message;
  EXPECT_TRUE(contains(message, "not a finite number")) << message;
  EXPECT_TRUE(contains(error_message([] {
                         make_env("Upkie-Mock-Servos", {{"nb_substeps", "2.5"}});
                       }),
                       "not an integer"));
  EXPECT_TRUE(contains(error_message([] {
                         make_env("Upkie-Mock-Servos", {{"frequency", "-5"}});
                       }),
                       "outside"));
  EXPECT_TRUE(contains(error_message([] {
                         make_env("Upkie-Mock-Servos", {{"inertia", "cube"}});
                       }),
                       "box, urdf"));
  EXPECT_TRUE(contains(error_message([] {
                         make_env("Upkie-Mock-Servos", {{"frequency", "nan"}});
                       }),
                       "not a finite number"));
}

TEST(Registry, ParseEnvOptions) {
  const EnvOptions options = parse_env_options({"fall_pitch=0.5", "inertia=urdf"});
  ASSERT_EQ(options.size(), 2u);
  EXPECT_EQ(options[0], (std::pair<std::string, std::string>{"fall_pitch", "0.5"}));
  EXPECT_EQ(options[1].second, "urdf");
  EXPECT_TRUE(contains(error_message([] { parse_env_options({"fall_pitch"}); }), "\"fall_pitch\""));
  EXPECT_FALSE(error_message([] { parse_env_options({"=1"}); }).empty());
  EXPECT_FALSE(error_message([] { parse_env_options({"a="}); }).empty());
}

TEST(Registry, OptionsAcceptedByEveryKind) {
  for (const std::string& id : registered_env_ids()) {
    if (id.find("Mock") == std::string::npos) continue;
    EXPECT_NO_THROW(make_env(id, {{"frequency", "100"},
                                  {"nb_substeps", "10"},
                                  {"inertia", "urdf"},
                                  {"init_rand_pitch", "0.1"},
                                  {"max_episode_steps", "50"}}))
        << id;
    EXPECT_FALSE(env_option_help(id).empty());
  }
}

TEST(Registry, SpineOptionsAreTheirOwn) {
  // A spine that is not there: a clear error after one attempt, not a hang.
  try {
    make_env("Upkie-Spine-Pendulum",
             {{"shm_name", "/upkie-rl-no-such-spine"}, {"open_tries", "1"}});
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& error) {
    EXPECT_TRUE(contains(error.what(), "upkie-rl-no-such-spine")) << error.what();
  }
  EXPECT_TRUE(contains(error_message([] {
                         make_env("Upkie-Spine-Servos", {{"nb_substeps", "5"}});
                       }),
                       "unknown option \"nb_substeps\""));
  EXPECT_TRUE(contains(error_message([] {
                         make_env("Upkie-Mock-Servos", {{"shm_name", "/x"}});
                       }),
                       "unknown option"));
  EXPECT_TRUE(contains(error_message([] {
                         make_env("Upkie-Spine-Servos", {{"regulate_frequency", "maybe"}});
                       }),
                       "true, false"));
}

TEST(Registry, InitRandomizationIsSeeded) {
  // Mock reports the reset joint angles but not the base pose; use the full observation's
  // ground truth of Bullet instead: the same seed gives the same initial state.
  auto a = make_env("Upkie-Bullet-Servos", {{"init_rand_pitch", "0.2"}, {"init_rand_x", "0.5"}});
  auto b = make_env("Upkie-Bullet-Servos", {{"init_rand_pitch", "0.2"}, {"init_rand_x", "0.5"}});
  std::vector<float> observation(30);
  a->reset(7, observation);
  b->reset(7, observation);
  const double xa = a->full_observation()->sim_base.position.x();
  EXPECT_DOUBLE_EQ(xa, b->full_observation()->sim_base.position.x());
  EXPECT_DOUBLE_EQ(a->full_observation()->base_orientation.pitch,
                   b->full_observation()->base_orientation.pitch);
  EXPECT_LE(std::abs(xa), 0.5);
  b->reset(8, observation);
  EXPECT_NE(xa, b->full_observation()->sim_base.position.x());
  // Without randomisation the reset state is the default.
  auto c = make_env("Upkie-Bullet-Servos");
  c->reset(7, observation);
  EXPECT_NEAR(c->full_observation()->sim_base.position.x(), 0.0, 1e-12);
}

TEST(Registry, OptionInfoIsTyped) {
  const std::vector<OptionInfo> options = env_option_info("Upkie-Bullet-Pendulum");
  auto find = [&options](const std::string& name) {
    for (const OptionInfo& option : options) {
      if (option.name == name) return option;
    }
    ADD_FAILURE() << "no option " << name;
    return OptionInfo{};
  };
  const OptionInfo frequency = find("frequency");
  EXPECT_EQ(frequency.type, OptionInfo::Type::kReal);
  EXPECT_EQ(frequency.default_value, "200");
  EXPECT_EQ(frequency.min, 1.0);
  EXPECT_EQ(frequency.max, 10000.0);
  const OptionInfo steps = find("max_episode_steps");
  EXPECT_EQ(steps.type, OptionInfo::Type::kInteger);
  EXPECT_EQ(steps.default_value, "300");
  const OptionInfo inertia = find("inertia");
  EXPECT_EQ(inertia.type, OptionInfo::Type::kChoice);
  EXPECT_EQ(inertia.choices, (std::vector<std::string>{"box", "urdf"}));
  EXPECT_EQ(find("max_ground_velocity").default_value, "1");
  const std::vector<OptionInfo> spine = env_option_info("Upkie-Spine-Servos");
  EXPECT_TRUE(std::any_of(spine.begin(), spine.end(), [](const OptionInfo& option) {
    return option.name == "shm_name" && option.type == OptionInfo::Type::kText;
  }));
  EXPECT_EQ(env_option_info("Upkie-Bullet-Servos").size(),
            env_option_help("Upkie-Bullet-Servos").size());
  EXPECT_THROW(env_option_info("Upkie-Nope-Servos"), std::invalid_argument);
}

}  // namespace
}  // namespace upkie_rl
