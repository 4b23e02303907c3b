// The rasteriser's shadows and anti-aliased edges from the command line (render, view, bench,
// aa-error): --shadows on|off, --shadow-cascades N and --msaa N (docs/cli.md, docs/renderer.md);
// the glint footprint policy (--footprint) and the cost tiers over these (--quality).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "gl/renderer.h"

namespace glint::app {

struct RasterOptions {
  std::string shadows = gl::FrameSettings{}.shadows ? "on" : "off";
  int shadowCascades = gl::FrameSettings{}.shadowCascades;
  int msaa = gl::FrameSettings{}.msaa;

  void addTo(CLI::App& command);
  // Sets the frame's shadows and samples a pixel; throws Error with one line for --shadows other
  // than on or off, for --shadow-cascades outside 1 to gl::kShadowCascades and for --msaa other
  // than a power of two that this OpenGL draws (the renderer's maxMsaaSamples).
  void applyTo(gl::FrameSettings& frame, const gl::Renderer& renderer) const;
};

// --footprint: how far the glint footprint may depart from the paper's to bound the cost of its walk
// (docs/cli.md, docs/antialiasing.md "Footprint policies"). render, view and trace take one policy;
// bench and aa-error take several (the option repeated), measured in the same run, frame by frame.
struct FootprintOptions {
  std::vector<std::string> policies;

  void addTo(CLI::App& command, bool several);
  // The policy given, exact when none; throws Error with one line naming --footprint.
  FootprintPolicy policy() const;
  // Each policy given, in order, with its name; exact alone when none.
  std::vector<std::pair<std::string, FootprintPolicy>> all() const;
};

// --quality: a cost tier (gl::qualityPresets; docs/cli.md) that sets --footprint, --aa and
// --shadow-cascades at once. render, view, bench and aa-error take it; each of those options given
// on the command line wins over the tier's value.
struct QualityOptions {
  std::string quality;  // the tier given, if any

  void addTo(CLI::App& command);
  // Sets what the tier sets and `command`'s line does not: the anti-aliasing mode's name, the
  // footprint policy and the cascades. Throws Error with one line naming --quality for an unknown tier.
  void applyTo(const CLI::App& command, std::string& antiAliasing, FootprintOptions& footprint,
               RasterOptions& raster) const;
};

// ", footprint P" for a run's summary line, empty for the paper's footprint.
std::string footprintNote(const FootprintPolicy& policy);

}  // namespace glint::app
