// The viewer's material and light controls (scene/view_controls.h): untouched controls leave every
// built-in scene bit for bit as loaded, and editing one material or one light changes that one only.
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "scene/builtin_scenes.h"
#include "scene/view_controls.h"

namespace glint {
namespace {

using scene::Light;
using scene::Material;

// Bit-for-bit comparison of every field (floats by their bits: -0 and 0 differ, a NaN equals itself).
std::uint32_t bits(float v) { return std::bit_cast<std::uint32_t>(v); }
template <int N>
bool same(const glm::vec<N, float>& a, const glm::vec<N, float>& b) {
  for (int i = 0; i < N; ++i) {
    if (bits(a[i]) != bits(b[i])) return false;
  }
  return true;
}
bool same(float a, float b) { return bits(a) == bits(b); }
bool same(const scene::UvTransform& a, const scene::UvTransform& b) {
  return same(a.offset, b.offset) && same(a.rotation, b.rotation) && same(a.scale, b.scale);
}
bool same(const scene::GlintLayer& a, const scene::GlintLayer& b) {
  return a.enabled == b.enabled && same(a.alpha, b.alpha) && same(a.rho, b.rho) && same(a.logDensity, b.logDensity) &&
         same(a.relativeArea, b.relativeArea) && same(a.densityRandomisation, b.densityRandomisation) &&
         same(a.maxAnisotropy, b.maxAnisotropy) && a.patternSeed == b.patternSeed && same(a.uvScale, b.uvScale) &&
         a.colouredCells == b.colouredCells && a.lod == b.lod && a.roughnessTexture == b.roughnessTexture &&
         a.logDensityTexture == b.logDensityTexture && same(a.logDensityRange, b.logDensityRange) &&
         a.relativeAreaTexture == b.relativeAreaTexture;
}
bool same(const Material& a, const Material& b) {
  return a.name == b.name && same(a.baseColour, b.baseColour) && a.baseColourTexture == b.baseColourTexture &&
         same(a.baseColourUv, b.baseColourUv) && same(a.metallicRoughnessUv, b.metallicRoughnessUv) &&
         same(a.normalUv, b.normalUv) && same(a.occlusionUv, b.occlusionUv) && same(a.emissiveUv, b.emissiveUv) &&
         same(a.metallic, b.metallic) && same(a.roughness, b.roughness) &&
         a.metallicRoughnessTexture == b.metallicRoughnessTexture && a.normalTexture == b.normalTexture &&
         same(a.normalScale, b.normalScale) && same(a.emissive, b.emissive) && a.emissiveTexture == b.emissiveTexture &&
         a.occlusionTexture == b.occlusionTexture && same(a.occlusionStrength, b.occlusionStrength) &&
         a.doubleSided == b.doubleSided && a.alphaMode == b.alphaMode && same(a.alphaCutoff, b.alphaCutoff) &&
         same(a.glint, b.glint) && a.specular.ndf == b.specular.ndf && a.specular.masking == b.specular.masking &&
         a.specular.multipleScattering == b.specular.multipleScattering;
}
bool same(const Light& a, const Light& b) {
  return a.type == b.type && same(a.position, b.position) && same(a.direction, b.direction) &&
         same(a.intensity, b.intensity) && same(a.innerConeAngle, b.innerConeAngle) &&
         same(a.outerConeAngle, b.outerConeAngle) && same(a.range, b.range);
}

// The scene's materials and lights as the viewer draws them under `controls`.
struct Drawn {
  std::vector<Material> materials;
  std::vector<Light> lights;
};
Drawn drawn(const scene::Scene& s, const scene::ViewControls& controls) {
  Drawn d;
  scene::applyViewControls(s, controls, scene::lightPivot(s), d.materials, d.lights);
  return d;
}

glm::vec3 direction(float azimuth, float elevation) {
  return {std::cos(elevation) * std::sin(azimuth), std::sin(elevation), std::cos(elevation) * std::cos(azimuth)};
}

TEST(ViewControls, UntouchedControlsLeaveEveryBuiltinSceneBitIdentical) {
  for (const std::string& name : scene::builtinSceneNames()) {
    const scene::Scene s = scene::makeBuiltinScene(name);
    const Drawn d = drawn(s, scene::viewControls(s, scene::lightPivot(s)));
    ASSERT_EQ(d.materials.size(), s.materials.size()) << name;
    ASSERT_EQ(d.lights.size(), s.lights.size()) << name;
    for (std::size_t i = 0; i < s.materials.size(); ++i) EXPECT_TRUE(same(d.materials[i], s.materials[i])) << name << " material " << i;
    for (std::size_t i = 0; i < s.lights.size(); ++i) EXPECT_TRUE(same(d.lights[i], s.lights[i])) << name << " light " << i;
  }
}

TEST(ViewControls, ControlsStartFromEachMaterialAndLight) {
  const scene::Scene s = scene::makeBuiltinScene("showroom");
  const glm::vec3 pivot = scene::lightPivot(s);
  const scene::ViewControls controls = scene::viewControls(s, pivot);
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    EXPECT_TRUE(same(controls.materials[i].alpha, s.materials[i].glint.alpha)) << s.materials[i].name;
    EXPECT_TRUE(same(controls.materials[i].logDensity, s.materials[i].glint.logDensity)) << s.materials[i].name;
  }
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const Light& light = s.lights[i];
    const scene::LightControls& c = controls.lights[i];
    const glm::vec3 towards = glm::normalize(light.position - pivot);
    EXPECT_LT(glm::length(direction(c.azimuth, c.elevation) - towards), 1e-6f) << "light " << i;
    EXPECT_EQ(c.strength, std::max({light.intensity.x, light.intensity.y, light.intensity.z})) << "light " << i;
  }
}

TEST(ViewControls, EditingOneMaterialLeavesEveryOtherBitIdentical) {
  for (const std::string& name : scene::builtinSceneNames()) {
    const scene::Scene s = scene::makeBuiltinScene(name);
    const scene::ViewControls untouched = scene::viewControls(s, scene::lightPivot(s));
    for (std::size_t k = 0; k < s.materials.size(); ++k) {
      if (!s.materials[k].glint.enabled) continue;
      scene::ViewControls controls = untouched;
      controls.materials[k] = {{0.123f, 0.456f}, 0.25f, 31.5f, 0.375f, scene::kGltfSpecular};
      const Drawn d = drawn(s, controls);
      const scene::GlintLayer& edited = d.materials[k].glint;
      EXPECT_EQ(edited.alpha, glm::vec2(0.123f, 0.456f));
      EXPECT_EQ(edited.rho, 0.25f);
      EXPECT_EQ(edited.logDensity, 31.5f);
      EXPECT_EQ(edited.relativeArea, 0.375f);
      EXPECT_EQ(d.materials[k].specular.ndf, kernel::GLINT_NDF_GGX);
      EXPECT_EQ(d.materials[k].specular.masking, kernel::GLINT_MASKING_SMITH);
      EXPECT_TRUE(d.materials[k].specular.multipleScattering);
      // Only those four and the specular target: the rest of the material, its glint textures
      // included, is the scene's.
      const scene::Material restored = scene::applyMaterialControls(d.materials[k], untouched.materials[k]);
      EXPECT_TRUE(same(restored, s.materials[k])) << name << " material " << k;
      for (std::size_t i = 0; i < s.materials.size(); ++i) {
        if (i != k) EXPECT_TRUE(same(d.materials[i], s.materials[i])) << name << ": editing " << k << " changed " << i;
      }
      for (std::size_t i = 0; i < s.lights.size(); ++i) EXPECT_TRUE(same(d.lights[i], s.lights[i])) << name;
    }
  }
}

TEST(ViewControls, MovingOneLightLeavesEveryOtherBitIdentical) {
  for (const std::string& name : scene::builtinSceneNames()) {
    const scene::Scene s = scene::makeBuiltinScene(name);
    const glm::vec3 pivot = scene::lightPivot(s);
    const scene::ViewControls untouched = scene::viewControls(s, pivot);
    for (std::size_t k = 0; k < s.lights.size(); ++k) {
      scene::ViewControls controls = untouched;
      scene::LightControls& c = controls.lights[k];
      c.azimuth = 1.1f;
      c.elevation = 0.4f;
      c.strength *= 2.0f;
      const Drawn d = drawn(s, controls);
      const Light& original = s.lights[k];
      const Light& moved = d.lights[k];
      const glm::vec3 towards = direction(1.1f, 0.4f);
      if (original.positional()) {
        const float distance = glm::length(original.position - pivot);
        EXPECT_NEAR(glm::length(moved.position - pivot), distance, 1e-5f * distance) << name << " light " << k;
        EXPECT_LT(glm::length(glm::normalize(moved.position - pivot) - towards), 1e-5f) << name << " light " << k;
      } else {
        EXPECT_LT(glm::length(moved.direction + towards), 1e-6f) << name << " light " << k;
      }
      EXPECT_LT(glm::length(moved.intensity - 2.0f * original.intensity), 1e-6f * glm::length(original.intensity))
          << name << " light " << k;
      for (std::size_t i = 0; i < s.lights.size(); ++i) {
        if (i != k) EXPECT_TRUE(same(d.lights[i], s.lights[i])) << name << ": moving " << k << " changed " << i;
      }
      for (std::size_t i = 0; i < s.materials.size(); ++i) EXPECT_TRUE(same(d.materials[i], s.materials[i])) << name;
    }
  }
}

TEST(ViewControls, ASpotTurnsWithItsPositionAndABlackLightBecomesWhite) {
  const glm::vec3 pivot(1.0f, 0.5f, -2.0f);
  Light spot;
  spot.type = Light::Type::Spot;
  spot.position = pivot + glm::vec3(0.0f, 3.0f, 4.0f);
  spot.direction = glm::normalize(pivot - spot.position);  // aimed at the pivot
  spot.intensity = glm::vec3(0.0f);
  scene::LightControls c = scene::lightControls(spot, pivot);
  EXPECT_NEAR(c.elevation, std::atan2(3.0f, 4.0f), 1e-6f);
  EXPECT_NEAR(c.azimuth, 0.0f, 1e-6f);
  EXPECT_EQ(c.strength, 0.0f);
  c.azimuth = -2.0f;
  c.elevation = 1.2f;
  c.strength = 7.0f;
  const Light moved = scene::applyLightControls(spot, c, pivot);
  EXPECT_NEAR(glm::length(moved.position - pivot), 5.0f, 1e-5f);
  EXPECT_LT(glm::length(moved.direction - glm::normalize(pivot - moved.position)), 1e-5f);  // still aimed at it
  EXPECT_EQ(moved.intensity, glm::vec3(7.0f));
  EXPECT_EQ(moved.outerConeAngle, spot.outerConeAngle);

  // A light at the pivot has no direction from it: straight up, and it stays where it is.
  Light point;
  point.position = pivot;
  point.intensity = glm::vec3(2.0f, 4.0f, 1.0f);
  scene::LightControls p = scene::lightControls(point, pivot);
  EXPECT_EQ(p.elevation, glm::half_pi<float>());
  EXPECT_EQ(p.strength, 4.0f);
  p.azimuth = 0.7f;
  p.strength = 8.0f;
  const Light same_place = scene::applyLightControls(point, p, pivot);
  EXPECT_EQ(same_place.position, pivot);
  EXPECT_EQ(same_place.intensity, glm::vec3(4.0f, 8.0f, 2.0f));  // twice as strong, same colour
}

}  // namespace
}  // namespace glint
