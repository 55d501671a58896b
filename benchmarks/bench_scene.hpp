#pragma once
// A benchmark's scene config, refused (with a message naming the program) when it is not of
// the kind the benchmark runs.
#include <cstdio>
#include <optional>
#include <string>

#include "fem/scenes/scene_config.hpp"

namespace softarm::bench {

inline std::optional<fem::SceneConfig> scene_of_kind(const std::string& config, const std::string& kind,
                                                     const char* program) {
  fem::SceneConfig scene = fem::load_scene_config(config);
  if (scene.scene == kind) return scene;
  std::fprintf(stderr, "%s: %s is a \"%s\" scene, not \"%s\"\n", program, config.c_str(), scene.scene.c_str(),
               kind.c_str());
  return std::nullopt;
}

}  // namespace softarm::bench
