// The specular lobe a renderer gives a material's glint layer (`--brdf` of `glint render`, `view`,
// `trace` and `bench`): one concept for both renderers (docs/architecture.md, "Adding a BRDF model").
#pragma once

#include <string>
#include <vector>

namespace glint {

// Glint: the layer's glint BRDF (Chermain et al. 2020, with the 2021 anti-aliasing where the
// renderer applies it). CookTorrance: its smooth limit, the target of the same roughness.
// ZirrKaplanyan: the baseline of Zirr & Kaplanyan 2016 with the layer's parameters mapped
// (kernel/zirr_kaplanyan.h); ZirrKaplanyanReference the same images on the reference shader's
// schedule, which only the rasteriser's timing tells apart (docs/zirr-kaplanyan.md, "Cost").
// A material without a glint layer is Cook-Torrance of its own roughness under every model.
enum class SpecularModel { Glint, CookTorrance, ZirrKaplanyan, ZirrKaplanyanReference };

// Every model, in the order tables list them.
std::vector<SpecularModel> allSpecularModels();
// "glint", "cook-torrance", "zirr-kaplanyan", "zirr-kaplanyan-reference".
const char* toString(SpecularModel model);
// Throws Error naming the choices.
SpecularModel specularModelFromName(const std::string& name);

}  // namespace glint
