// The layering of src/, checked on every include line rather than asserted in the docs: a
// file of layer L includes headers of L and of the layers below it only (cmake/layers.txt,
// the one declaration of the order), never of a layer above nor of a sibling on L's rank.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace upkie_rl {
namespace {

/// Rank of each layer: its line's index among the non-comment lines of layers.txt.
using LayerRanks = std::map<std::string, int>;

LayerRanks parse_layer_ranks(const std::string& text) {
  LayerRanks ranks;
  std::istringstream lines(text);
  std::string line;
  int rank = 0;
  while (std::getline(lines, line)) {
    if (line.empty() || line.front() == '#') continue;
    std::istringstream names(line);
    std::string name;
    while (names >> name) ranks[name] = rank;
    ++rank;
  }
  return ranks;
}

/// The first folder of a quoted include ("envs/tasks/x.hpp" -> "envs"), or "" for a line
/// that is not a quoted include with a folder (system headers, a file's own folder-less
/// neighbour).
std::string included_layer(std::string_view line) {
  const std::size_t start = line.find_first_not_of(" \t");
  if (start == std::string_view::npos) return "";
  line.remove_prefix(start);
  constexpr std::string_view kQuotedInclude = "#include \"";
  if (line.substr(0, kQuotedInclude.size()) != kQuotedInclude) return "";
  line.remove_prefix(kQuotedInclude.size());
  const std::size_t slash = line.find('/');
  const std::size_t quote = line.find('"');
  if (slash == std::string_view::npos || quote == std::string_view::npos || slash > quote) {
    return "";
  }
  return std::string(line.substr(0, slash));
}

/// "file: #include line" for each include of `text` (a file of `layer`) that reaches a layer
/// above `layer` or a sibling of it. Folders that are not layers (external libraries'
/// "CLI/CLI.hpp") are not checked.
std::vector<std::string> upward_includes(const LayerRanks& ranks, const std::string& layer,
                                         const std::string& file, const std::string& text) {
  std::vector<std::string> found;
  const int own_rank = ranks.at(layer);
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    const std::string target = included_layer(line);
    const auto rank = ranks.find(target);
    if (rank == ranks.end() || target == layer) continue;
    if (rank->second >= own_rank) found.push_back(file + ": " + line);
  }
  return found;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream stream(path);
  std::stringstream text;
  text << stream.rdbuf();
  return text.str();
}

const std::filesystem::path kSources = std::filesystem::path(UPKIE_RL_SOURCE_DIR) / "src";

LayerRanks declared_ranks() {
  return parse_layer_ranks(
      read_text(std::filesystem::path(UPKIE_RL_SOURCE_DIR) / "cmake" / "layers.txt"));
}

TEST(Layering, OrderFileRanksLayersAndSiblings) {
  const LayerRanks ranks = parse_layer_ranks("# comment\nbase\nsim\nrender view\n\nenvs\n");
  EXPECT_EQ(ranks, (LayerRanks{{"base", 0}, {"sim", 1}, {"render", 2}, {"view", 2}, {"envs", 3}}));
}

TEST(Layering, IncludedLayerIsTheFirstFolderOfAQuotedInclude) {
  EXPECT_EQ(included_layer("#include \"envs/tasks/velocity_task.hpp\""), "envs");
  EXPECT_EQ(included_layer("  #include \"rl/ppo/ppo.hpp\"  // why"), "rl");
  EXPECT_EQ(included_layer("#include <Eigen/Core>"), "");
  EXPECT_EQ(included_layer("#include \"tinyxml.h\""), "");
  EXPECT_EQ(included_layer("// #include \"rl/ppo/ppo.hpp\""), "");
}

// The checker itself, on an in-memory file: it must catch what the real tree must not have.
TEST(Layering, CheckerRefusesUpwardAndSiblingIncludes) {
  const LayerRanks ranks = parse_layer_ranks("base\nmodel\nsim\nrender view\nenvs\nrl\n");
  const std::string file =
      "#include \"model/robot_model.hpp\"\n"
      "\n"
      "#include <vector>\n"
      "#include \"base/trim.hpp\"\n"
      "#include \"rl/ppo/ppo.hpp\"\n"
      "#include \"view/view_server.hpp\"\n"
      "#include \"CLI/CLI.hpp\"\n";
  const std::vector<std::string> model_found = upward_includes(ranks, "model", "m.cpp", file);
  EXPECT_EQ(model_found, (std::vector<std::string>{"m.cpp: #include \"rl/ppo/ppo.hpp\"",
                                                   "m.cpp: #include \"view/view_server.hpp\""}));
  // A sibling (render and view share a rank) is refused; the layer's own headers are not.
  const std::vector<std::string> render_found = upward_includes(ranks, "render", "r.cpp", file);
  EXPECT_EQ(render_found, (std::vector<std::string>{"r.cpp: #include \"rl/ppo/ppo.hpp\"",
                                                    "r.cpp: #include \"view/view_server.hpp\""}));
  EXPECT_TRUE(upward_includes(ranks, "view", "v.cpp",
                              "#include \"view/x.hpp\"\n#include "
                              "\"sim/y.hpp\"\n")
                  .empty());
  EXPECT_TRUE(upward_includes(ranks, "rl", "l.cpp", file).empty());
}

TEST(Layering, EveryFolderOfSrcIsALayer) {
  const LayerRanks ranks = declared_ranks();
  ASSERT_FALSE(ranks.empty());
  for (const auto& entry : std::filesystem::directory_iterator(kSources)) {
    if (!entry.is_directory()) continue;
    const std::string layer = entry.path().filename().string();
    EXPECT_TRUE(ranks.contains(layer)) << "src/" << layer << " is not in cmake/layers.txt";
  }
}

TEST(Layering, NoFileIncludesALayerAboveItsOwn) {
  const LayerRanks ranks = declared_ranks();
  std::vector<std::string> found;
  int files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kSources)) {
    if (!entry.is_regular_file()) continue;
    const std::filesystem::path relative = entry.path().lexically_relative(kSources);
    const std::string layer = relative.begin()->string();
    if (!ranks.contains(layer)) continue;  // EveryFolderOfSrcIsALayer reports it.
    const std::vector<std::string> file_found =
        upward_includes(ranks, layer, relative.string(), read_text(entry.path()));
    found.insert(found.end(), file_found.begin(), file_found.end());
    ++files;
  }
  EXPECT_GT(files, 400);
  EXPECT_TRUE(found.empty()) << "includes of a higher or sibling layer:\n"
                             << ::testing::PrintToString(found);
}

}  // namespace
}  // namespace upkie_rl
