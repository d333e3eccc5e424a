#pragma once
/// @file
/// The flags several commands share, each declared once here so that it has one name, one
/// meaning, one default and one check in every command (the viewer's flags are in
/// live_view.hpp, --controller's help in controller_option.hpp).

#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_failure.hpp"

namespace upkie_rl::apps {

/// Default of --max-steps in rollout and evaluate: the velocity tasks' episode (20 s at
/// 50 Hz), longer than the pendulum's time limit (300 steps), which ends its episodes first.
inline constexpr int kDefaultMaxSteps = 1000;

/// --env: an environment id, checked against the registry (a mistyped id gets the nearest
/// one suggested) before the command runs.
CLI::Option* add_env_id_option(CLI::App& command, std::string& env_id,
                               const std::string& help = "Environment id (see `upkie-rl envs`)");

/// --env-option key=value, repeatable; `scope` (" for every cell") follows "key=value" in
/// the help.
CLI::Option* add_env_option_option(CLI::App& command, std::vector<std::string>& env_options,
                                   const std::string& scope = "");

/// --episodes N: how many episodes to run, in [1, kMaxEvaluationEpisodes] (the bound of
/// `upkie_rl.evaluate(episodes=...)` too: a typo cannot start a run that never ends). Its help
/// is "Number of episodes" then `scope` (" per cell and controller"); its default, shown in
/// the help, is the caller's: the value of `episodes` when called.
CLI::Option* add_episodes_option(CLI::App& command, int& episodes, const std::string& scope = "");

/// Whether --help shows a flag's default: not where an absent flag means "the
/// configuration's own" (train's --seed), which a figure would misstate.
enum class DefaultInHelp { kShown, kHidden };

/// --seed S: a seed in [0, 2^64 - 1] (kSeed: "-1" and 2^64 are refused, not wrapped). Its help
/// is "Seed of " then `of_what` ("the fit"); its default is the caller's: the value of `seed`
/// when called.
CLI::Option* add_seed_option(CLI::App& command, std::uint64_t& seed, const std::string& of_what,
                             DefaultInHelp default_in_help = DefaultInHelp::kShown);

/// --threads N: the work (`work`: what the threads run) on N threads; 0: in the calling
/// thread, without a thread pool. The default is the caller's.
CLI::Option* add_threads_option(CLI::App& command, int& threads, const std::string& work);

/// One thread per core (at least one): the default of --threads where the work is independent
/// episodes (evaluate).
int one_thread_per_core();

/// --max-steps N (default kDefaultMaxSteps): an episode also ends after N steps;
/// `meaning` says what that means for the command.
CLI::Option* add_max_steps_option(CLI::App& command, int& max_steps, const std::string& meaning);

/// --json: the command's summary as JSON on the last line of its output.
CLI::Option* add_json_flag(CLI::App& command, bool& json);

/// A former spelling `alias` of option `current`, setting the same variable with the same
/// `check` and left out of --help (group kFormerSpellings, which HelpWithoutFormerSpellings
/// leaves out); a value it accepts prints one line "upkie-rl: note: <command> <alias> is now
/// <current>" on the standard error.
template <typename Value>
void add_former_spelling(CLI::App& command, const std::string& alias, const std::string& current,
                         Value& target, const CLI::Validator& check = CLI::Validator());

/// CLI11's help without the group kFormerSpellings.
class HelpWithoutFormerSpellings : public CLI::Formatter {
 public:
  std::string make_group(std::string group, bool is_positional,
                         std::vector<const CLI::Option*> options) const override {
    if (group == kFormerSpellings) return "";
    return CLI::Formatter::make_group(std::move(group), is_positional, std::move(options));
  }
};

/// The note of add_former_spelling ("<used> is now <current>"), as a check that passes every
/// value.
CLI::Validator former_spelling_note(const std::string& used, const std::string& current);

template <typename Value>
void add_former_spelling(CLI::App& command, const std::string& alias, const std::string& current,
                         Value& target, const CLI::Validator& check) {
  command.formatter(std::make_shared<HelpWithoutFormerSpellings>());
  command.add_option(alias, target)
      ->group(kFormerSpellings)
      ->check(check)
      ->check(former_spelling_note(command.get_name() + " " + alias, current));
}

}  // namespace upkie_rl::apps
