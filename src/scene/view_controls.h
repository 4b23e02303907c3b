// What the viewer's sliders edit (glint view: one glint material and one light at a time), as pure
// functions of the scene so that they are tested without a window. Controls are read from the
// scene as loaded and applied to it afresh every frame; controls that are read and applied back
// untouched give the scene bit for bit, so the viewer opens on exactly what `glint render` draws.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::scene {

// The constants of a glint layer that the sliders edit, and the material's specular target; the
// layer's textures (which multiply or replace them) and its other fields stay as the scene has them.
// Before they are read from a material: a default layer's (glint_fields.h).
struct MaterialControls {
  glm::vec2 alpha = GlintLayer().alpha;  // roughness alpha_x, alpha_y
  float rho = GlintLayer().rho;
  float logDensity = GlintLayer().logDensity;
  float relativeArea = GlintLayer().relativeArea;
  MicrofacetTarget specular;  // Material::specular
};

// A light as seen from a pivot (the scene's centre): the direction from the pivot towards it, as
// an azimuth (radians about +y, 0 towards +z, pi/2 towards +x) and an elevation (radians above the
// horizontal plane), and its strength, the largest component of its intensity (W/sr for point and
// spot lights, W/m^2 for directional ones).
struct LightControls {
  float azimuth = 0.0f;
  float elevation = 0.0f;
  float strength = 0.0f;
};

// One set of controls per material (those without a glint layer are never shown, and applying
// them changes nothing) and one per light of the scene.
struct ViewControls {
  std::vector<MaterialControls> materials;
  std::vector<LightControls> lights;
};

MaterialControls materialControls(const Material& material);
// The material with the controls in its glint layer.
Material applyMaterialControls(const Material& material, const MaterialControls& controls);

// Azimuth and elevation of the direction towards a directional light (against the direction it
// travels), or from the pivot to a point or spot light; straight up for a light at the pivot.
LightControls lightControls(const Light& light, glm::vec3 pivot);
// The light moved to the controls' direction and given their strength. A point or spot light keeps
// its distance to the pivot, and a spot's axis turns with it (a spot aimed at the pivot stays aimed
// at it). The colour, the ratio of the intensity's components, is kept; a black light becomes
// white. The direction is rebuilt only when the angles differ from the light's own and the
// intensity only when the strength does: the round trip through angles is not exact in floats,
// and untouched controls must leave the light as it is.
Light applyLightControls(const Light& light, const LightControls& controls, glm::vec3 pivot);

// The pivot of the light controls: the centre of the scene's bounds.
glm::vec3 lightPivot(const Scene& scene);

// Controls for every material and light of the scene, as it has them.
ViewControls viewControls(const Scene& scene, glm::vec3 pivot);
// The scene's materials and lights with `controls` applied (one each per material and light of
// the scene), into `materials` and `lights` (the renderer's, drawn on the next frame).
void applyViewControls(const Scene& scene, const ViewControls& controls, glm::vec3 pivot,
                       std::vector<Material>& materials, std::vector<Light>& lights);

}  // namespace glint::scene
