// The layers of the source tree, read from its #include lines: dependencies point one way,
// engine/ → studies/, objectives/ → fem/, and neither folders nor files form cycles. A file here is
// a unit (x.hpp with x.cpp): x.cpp including y.hpp and y.cpp including x.hpp is a cycle of units.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;
using Graph = std::map<std::string, std::set<std::string>>;

struct Includes {
  Graph folders, units;
};

// Every project include (a path with a folder) of every source under the top-level folders.
Includes read_includes() {
  static const std::regex include_line(R"re(^\s*#\s*include\s+"([^"]+/[^"]+)\.(hpp|cpp|h)")re");
  Includes g;
  for (const char* top : {"engine", "studies", "objectives", "fem"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(SOFTARM_SOURCE_DIR) / top)) {
      const fs::path& p = entry.path();
      if (p.extension() != ".hpp" && p.extension() != ".cpp") continue;
      const std::string relative = fs::relative(p, SOFTARM_SOURCE_DIR).generic_string();
      const std::string unit = relative.substr(0, relative.rfind('.'));
      const std::string folder = fs::path(relative).parent_path().generic_string();
      g.units[unit];
      g.folders[folder];
      std::ifstream in(p);
      std::string line;
      std::smatch m;
      while (std::getline(in, line)) {
        if (!std::regex_search(line, m, include_line)) continue;
        const std::string target = m[1];
        const std::string target_folder = fs::path(target).parent_path().generic_string();
        if (target != unit) g.units[unit].insert(target);
        if (target_folder != folder) g.folders[folder].insert(target_folder);
      }
    }
  }
  return g;
}

// The strongly connected components with more than one member (Tarjan): each is a cycle.
std::vector<std::vector<std::string>> cycles(const Graph& graph) {
  std::map<std::string, int> index, low;
  std::set<std::string> on_stack;
  std::vector<std::string> stack;
  std::vector<std::vector<std::string>> found;
  int counter = 0;
  std::function<void(const std::string&)> visit = [&](const std::string& v) {
    index[v] = low[v] = counter++;
    stack.push_back(v);
    on_stack.insert(v);
    if (const auto it = graph.find(v); it != graph.end())
      for (const std::string& w : it->second) {
        if (!index.count(w)) {
          visit(w);
          low[v] = std::min(low[v], low[w]);
        } else if (on_stack.count(w)) {
          low[v] = std::min(low[v], index[w]);
        }
      }
    if (low[v] != index[v]) return;
    std::vector<std::string> component;
    std::string w;
    do {
      w = stack.back();
      stack.pop_back();
      on_stack.erase(w);
      component.push_back(w);
    } while (w != v);
    if (component.size() > 1) found.push_back(component);
  };
  for (const auto& [v, edges] : graph)
    if (!index.count(v)) visit(v);
  return found;
}

std::string words(const std::vector<std::vector<std::string>>& found) {
  std::ostringstream s;
  for (const auto& c : found) {
    s << "cycle:";
    for (const auto& v : c) s << " " << v;
    s << "\n";
  }
  return s.str();
}

int layer(const std::string& folder) {
  const std::string top = folder.substr(0, folder.find('/'));
  if (top == "fem") return 0;
  if (top == "objectives" || top == "studies") return 1;
  return 2;  // engine
}
}  // namespace

TEST_CASE("The source tree's includes point one way and form no cycles", "[layers]") {
  const Includes g = read_includes();
  REQUIRE(g.units.size() > 100);  // the tree was found

  SECTION("the cycle finder finds a cycle") {
    Graph toy{{"a", {"b"}}, {"b", {"c"}}, {"c", {"a"}}, {"d", {"a"}}};
    const auto found = cycles(toy);
    REQUIRE(found.size() == 1);
    CHECK(found[0].size() == 3);
  }
  SECTION("no folder cycles") {
    const auto found = cycles(g.folders);
    INFO(words(found));
    CHECK(found.empty());
  }
  SECTION("no file cycles") {
    const auto found = cycles(g.units);
    INFO(words(found));
    CHECK(found.empty());
  }
  SECTION("fem/ knows nothing of the layers above it; objectives/ and studies/ nothing of engine/") {
    std::vector<std::string> upward;
    for (const auto& [folder, targets] : g.folders)
      for (const std::string& t : targets)
        if (layer(t) > layer(folder)) upward.push_back(folder + " -> " + t);
    INFO(Catch::Detail::stringify(upward));
    CHECK(upward.empty());
  }
}
