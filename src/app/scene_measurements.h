// What the measuring commands (aa-error, lod-consistency) do with each scene: measure it, add its
// figures to the report's "scenes" and say on stderr how long it took, as progress on long work.
#pragma once

#include <chrono>
#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace glint::app {

// measure(scene) returns the scene's JSON entry.
template <class Measure>
void measureScenes(const std::vector<scene::Scene>& scenes, nlohmann::json& report, Measure measure) {
  for (const scene::Scene& scene : scenes) {
    const auto start = std::chrono::steady_clock::now();
    report["scenes"].push_back(measure(scene));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "glint: measured %s in %.1f s\n", scene.name.c_str(), seconds);
  }
}

}  // namespace glint::app
