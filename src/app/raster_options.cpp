#include "app/raster_options.h"

#include "glint/error.h"

namespace glint::app {

void FootprintOptions::addTo(CLI::App& command, bool several) {
  const std::string help =
      "Glint pixel footprint: exact (the paper's), or aniso=A (anisotropy at most A), cells=K (each walked "
      "level at most K cells, K >= 12), drop=W (the coarser level skipped below blend weight W), joined by "
      "commas";
  CLI::Option* option = command.add_option(
      "--footprint", policies,
      several ? help + "; repeat it to measure several policies in the same run" : help);
  option->allow_extra_args(false);
  if (!several) option->expected(1);
}

std::vector<std::pair<std::string, FootprintPolicy>> FootprintOptions::all() const {
  std::vector<std::pair<std::string, FootprintPolicy>> result;
  for (const std::string& text : policies) {
    try {
      const FootprintPolicy policy = footprintPolicyFromString(text);
      for (const auto& [name, earlier] : result) {
        if (name == footprintPolicyName(policy)) throw Error("policy '" + text + "' is given twice");
      }
      result.emplace_back(footprintPolicyName(policy), policy);
    } catch (const Error& error) {
      throw Error(std::string("--footprint: ") + error.what());
    }
  }
  if (result.empty()) result.emplace_back("exact", exactFootprintPolicy());
  return result;
}

FootprintPolicy FootprintOptions::policy() const {
  if (policies.size() > 1) throw Error("--footprint is given more than once");
  return all().front().second;
}

std::string footprintNote(const FootprintPolicy& policy) {
  const std::string name = footprintPolicyName(policy);
  return name == "exact" ? "" : ", footprint " + name;
}

void RasterOptions::addTo(CLI::App& command) {
  command.add_option("--shadows", shadows,
                     "Shadows of the lights (shadow maps, filtered edges): on or off")
      ->capture_default_str();
  command.add_option("--shadow-cascades", shadowCascades,
                     "Shadow maps of a directional light, each over a range of the view's depth: 1 to " +
                         std::to_string(gl::kShadowCascades) + "; 1 fits one map to the whole scene")
      ->capture_default_str();
  command.add_option("--msaa", msaa,
                     "Samples a pixel of the geometry, for anti-aliased edges: each surface in a pixel is still "
                     "shaded once, at its centre; 1 turns it off")
      ->capture_default_str();
}

void RasterOptions::applyTo(gl::FrameSettings& frame, const gl::Renderer& renderer) const {
  if (shadows != "on" && shadows != "off") throw Error("--shadows must be on or off, got '" + shadows + "'");
  if (shadowCascades < 1 || shadowCascades > gl::kShadowCascades) {
    throw Error("--shadow-cascades must be from 1 to " + std::to_string(gl::kShadowCascades) + ", got " +
                std::to_string(shadowCascades));
  }
  const int most = renderer.maxMsaaSamples();
  if (msaa < 1 || (msaa & (msaa - 1)) != 0 || msaa > most) {
    throw Error("--msaa must be a power of two from 1 to " + std::to_string(most) + " (this OpenGL's most), got " +
                std::to_string(msaa));
  }
  frame.shadows = shadows == "on";
  frame.shadowCascades = shadowCascades;
  frame.msaa = msaa;
}

void QualityOptions::addTo(CLI::App& command) {
  std::string tiers;
  for (const gl::QualityPreset& preset : gl::qualityPresets()) tiers += (tiers.empty() ? "" : ", ") + std::string(preset.name);
  command.add_option("--quality", quality,
                     "Cost tier: " + tiers + ", each a preset of --footprint, --aa and --shadow-cascades (any of "
                     "them given wins); exact is the defaults");
}

void QualityOptions::applyTo(const CLI::App& command, std::string& antiAliasing, FootprintOptions& footprint,
                             RasterOptions& raster) const {
  if (command.get_option("--quality")->count() == 0) return;
  const gl::QualityPreset* preset = nullptr;
  try {
    preset = &gl::qualityPreset(quality);
  } catch (const Error& error) {
    throw Error(std::string("--quality: ") + error.what());
  }
  if (command.get_option("--aa")->count() == 0) antiAliasing = gl::toString(preset->antiAliasing);
  if (footprint.policies.empty()) footprint.policies = {preset->footprint};
  if (command.get_option("--shadow-cascades")->count() == 0) raster.shadowCascades = preset->shadowCascades;
}

}  // namespace glint::app
