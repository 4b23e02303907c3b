// A renderable scene, independent of OpenGL: world-space triangle meshes, glTF-style materials
// with an optional glint layer, lights, an environment and named cameras. Built by the glTF
// loader (gltf_loader.h) or by the built-in scenes (builtin_scenes.h); drawn by src/gl and traced
// by src/trace.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "glint/bsdf.h"
#include "glint/glint_fields.h"
#include "glint/kernel/glint_material.h"

namespace glint::scene {

struct Vertex {
  glm::vec3 position;  // world space (node transforms are baked in at load time)
  glm::vec3 normal;    // unit length
  glm::vec4 tangent;   // xyz unit tangent along +u, w = handedness (+1 or -1); generated when missing
  glm::vec2 uv;
  glm::vec4 colour{1.0f};  // glTF COLOR_0, linear RGBA: multiplies the base colour and its alpha; white when missing
};

struct Mesh {
  std::string name;
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;  // triangles
  int material = 0;                    // index into Scene::materials
};

// How a texture is sampled: glTF's sampler (samplers[], OpenGL's wrap modes and filters). The
// defaults are glTF's repeat and, where a file names no filter, the trilinear filtering viewers use.
struct TextureSampler {
  enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };
  enum class Mipmap { None, Nearest, Linear };
  Wrap wrapS = Wrap::Repeat;  // along u
  Wrap wrapT = Wrap::Repeat;  // along v
  bool magnifyNearest = false;     // magFilter NEAREST
  bool minifyNearest = false;      // minFilter NEAREST or NEAREST_MIPMAP_*: the nearest texel of a level
  Mipmap mipmap = Mipmap::Linear;  // minFilter NEAREST or LINEAR: none; *_MIPMAP_NEAREST; *_MIPMAP_LINEAR
  bool operator==(const TextureSampler&) const = default;
};

// 8-bit RGBA texels, rows from the top of the image (as glTF images are stored).
struct Texture {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
  bool srgb = false;  // colour textures (base colour, emissive) are sRGB; data textures linear
  TextureSampler sampler;
};

// The glint layer of a material (docs/scenes.md, "Glint parameters in glTF"): the kernel's material
// block (kernel/glint_material.h; its fields' names, defaults, ranges and meaning are
// glint_fields.h's table, kGlintFields) and the layer's textures. When enabled, the material's
// specular lobe is the glint BRDF; with `--brdf cook-torrance` it is Cook-Torrance with the same
// roughness. The block's ndf, masking and multipleScattering are the material's specular target
// (Material::specular), and hasLogDensityTexture follows logDensityTexture: glintMaterial() writes
// them when it packs the layer for a renderer, so a renderer reads the block only through it.
struct GlintLayer : kernel::GlintMaterial {
  GlintLayer() : kernel::GlintMaterial(glintDefaultMaterial()) {}
  // Optional textures (indices into Scene::textures, -1 for none); each multiplies or replaces
  // the constant of the block as documented in docs/scenes.md.
  int roughnessTexture = -1;       // R channel multiplies alpha (result clamped to [0.01, 2])
  int logDensityTexture = -1;      // R channel maps linearly onto logDensityRange
  int relativeAreaTexture = -1;    // R channel multiplies relativeArea
};

// glTF KHR_texture_transform on one texture of a material: uv' = offset + R (scale * uv), where R
// turns uv by `rotation` radians as the extension's example and its known implementations do
// (u' = u cos + v sin, v' = v cos - u sin: counter-clockwise in glTF's uv, whose v runs down the
// image). The identity when the file has none.
struct UvTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};

  glm::mat2 linear() const;  // R * diag(scale): what uv derivatives are multiplied by
  glm::vec2 apply(glm::vec2 uv) const { return linear() * uv + offset; }
  bool identity() const { return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f); }
  glm::mat3x2 matrix() const {  // for GLSL: M * vec3(uv, 1)
    const glm::mat2 l = linear();
    return glm::mat3x2(l[0], l[1], offset);
  }
};

// glTF 2.0 metal-roughness material.
struct Material {
  std::string name;
  glm::vec4 baseColour{1.0f};
  int baseColourTexture = -1;
  // Each texture's KHR_texture_transform.
  UvTransform baseColourUv, metallicRoughnessUv, normalUv, occlusionUv, emissiveUv;
  float metallic = 0.0f;
  float roughness = 0.5f;             // perceptual; alpha = roughness^2 for the non-glint specular
  int metallicRoughnessTexture = -1;  // G = roughness, B = metallic (glTF convention)
  int normalTexture = -1;
  float normalScale = 1.0f;
  glm::vec3 emissive{0.0f};  // emissiveFactor, times KHR_materials_emissive_strength's strength
  int emissiveTexture = -1;
  int occlusionTexture = -1;
  float occlusionStrength = 1.0f;  // glTF occlusionTexture.strength: occlusion = 1 + strength (texel - 1)
  // glTF's doubleSided: when false the rasteriser culls back faces (counter-clockwise triangles are
  // front faces); when true both sides are drawn, a back face shaded with its normal turned to the
  // camera. The path tracer sees both sides of every triangle either way.
  bool doubleSided = false;
  // glTF's alphaMode: OPAQUE ignores alpha; MASK drops the surface where the base colour's alpha
  // (factor times texture) is below alphaCutoff, in both renderers; BLEND is drawn opaque (glint
  // has no alpha blending; the command line warns).
  enum class AlphaMode { Opaque, Mask, Blend };
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  // glTF's KHR_materials_clearcoat: a clear dielectric coat over everything else, the glint layer
  // included (kernel/clearcoat.h). factor 0: none.
  struct Clearcoat {
    float factor = 0.0f;     // clearcoatFactor, times clearcoatTexture's R
    float roughness = 0.0f;  // clearcoatRoughnessFactor, times clearcoatRoughnessTexture's G
    int texture = -1;
    int roughnessTexture = -1;
    int normalTexture = -1;  // the coat's own normal map; without one the coat follows the interpolated normal
    float normalScale = 1.0f;
    UvTransform uv, roughnessUv, normalUv;  // each texture's KHR_texture_transform
    bool enabled() const { return factor > 0.0f; }
    bool hasTextures() const { return texture >= 0 || roughnessTexture >= 0 || normalTexture >= 0; }
  };
  Clearcoat clearcoat;
  GlintLayer glint;
  // The specular lobe's smooth target, masking and multiple-scattering compensation
  // (kernel/microfacet_targets.h, kernel/multiple_scattering.h), with or without a glint layer (the
  // layer converges to it): a glTF file's materials get glTF's, GGX with Smith masking and the
  // compensation (kGltfSpecular); the built-in scenes the 2020 paper's, Beckmann with V-cavity.
  MicrofacetTarget specular;
};

// glTF's metallic-roughness specular lobe: GGX, height-correlated Smith, and the compensation of
// the energy its single scattering loses: EXT_materials_glint's defaults (glint_fields.h).
inline constexpr MicrofacetTarget kGltfSpecular{glintDefaultChoice(GlintField::Ndf), glintDefaultChoice(GlintField::Masking),
                                                glintDefaultBoolean(GlintField::MultipleScattering)};

struct Light {
  enum class Type { Point, Directional, Spot };
  Type type = Type::Point;
  glm::vec3 position{0.0f};        // point and spot lights
  glm::vec3 direction{0, -1, 0};   // directional lights: the direction the light travels; spots: their axis
  glm::vec3 intensity{1.0f};       // point, spot: W/sr (radiant intensity, on the axis); directional: W/m^2
  float innerConeAngle = 0.0f;     // spots, radians from the axis: full intensity within the inner
  float outerConeAngle = 0.7853982f;  // cone, none beyond the outer (kernel/lights.h)
  float range = 0.0f;              // point and spot lights: dark from this distance on (kernel/lights.h); 0: no range

  bool positional() const { return type != Type::Directional; }
  // kernel::glintSpotConeScaleOffset of a spot's cones; (0, 1), no falloff, for the other lights.
  glm::vec2 coneScaleOffset() const;
  // A spot's unit axis, as kernel::glintSpotAttenuation takes it; any unit vector for the other lights,
  // whose cone (0, 1) ignores it.
  glm::vec3 spotAxis() const;
  // 1 / range, as kernel::glintRangeWindow takes it; 0 for a light without a range and for directional
  // lights.
  float inverseRange() const;
};

// Ambient light: an equirectangular radiance map (linear RGB, rows from the top, +y up); a
// uniform colour when `pixels` is empty.
struct Environment {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;
  glm::vec3 uniform{0.0f};
  float intensity = 1.0f;
  // The map turned about +y by this angle (radians, counter-clockwise seen from above): a direction
  // d of the world reads the map at mapDirection(d). Both renderers apply it.
  float rotation = 0.0f;
  // How many of the map's brightest small regions the rasteriser takes out as directional lights,
  // so that they light glints (scene/environment_map.h, extractEnvironmentLights); the path tracer
  // samples the whole map and ignores it.
  int rasterLights = 4;
  // How many of the rest's brightest regions light glints in the rasteriser
  // (scene/environment_map.h, environmentGlintRegions); the path tracer ignores it too.
  int rasterRegions = 0;

  glm::vec3 mapDirection(glm::vec3 world) const;  // world to map: turned by -rotation
  glm::vec3 worldDirection(glm::vec3 map) const;  // map to world: turned by +rotation
};

// A camera looks from position towards target. glTF's two projections: a perspective camera is a
// pinhole at position that sees verticalFovDegrees; an orthographic one sees a view
// 2 * orthographicHalfHeight high along the view direction, from the plane through position
// perpendicular to it. Either way the image's size sets the aspect ratio.
struct Camera {
  enum class Projection { Perspective, Orthographic };
  glm::vec3 position{0, 0, 3};
  glm::vec3 target{0.0f};
  glm::vec3 up{0, 1, 0};
  Projection projection = Projection::Perspective;
  float verticalFovDegrees = 45.0f;      // perspective
  float orthographicHalfHeight = 1.0f;   // orthographic, scene units (glTF's ymag)
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Light> lights;
  // True when `lights` are the ones addDefaultLighting invented for a file that brings none: an
  // environment given by the user (--env, --sky) replaces them (app::SceneOptions::loadScene).
  bool defaultLights = false;
  Environment environment;
  std::map<std::string, Camera> cameras;  // always holds "default"
  // The bounding box's presets as glint made them when it loaded or built the scene
  // (standardCameras), before anything added to it (a --rect-light's quad) moved the bounds: `glint
  // export` leaves out a camera that is still one of them.
  std::map<std::string, Camera> presetCameras;
  float exposure = 1.0f;
  // What the scene's file uses that glint does not render (vertex colours, a second uv set, an
  // extension it does not read, ...), one line each, for the commands to warn about.
  std::vector<std::string> unreadFeatures;
  // What the file holds in an older form that glint still reads, with what writes the current one
  // (extras.glint: `glint export` writes EXT_materials_glint), one line each, for the commands to
  // say.
  std::vector<std::string> notes;

  // Bounds of all vertices.
  glm::vec3 boundsMin() const;
  glm::vec3 boundsMax() const;
};

// Rec. 709 luminance of linear RGB: how lobes, emitters and environment texels are weighed.
inline float luminance(glm::vec3 c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// The glint roughness of a material whose glint layer gives no alpha: roughness^2 (the glTF
// convention), at least 0.01 so the glint BRDF stays within its dictionary.
float alphaFromRoughness(float roughness);

// A glint layer with the material's specular target as the renderers store it (the rasteriser's
// uniform block, the path tracer's shading): kernel::glintMaterialParameters makes the kernel's
// parameters of it and the layer's texture samples at a shading point. A disabled layer packs
// with enabled = 0.
kernel::GlintMaterial glintMaterial(const GlintLayer& layer, const MicrofacetTarget& target = MicrofacetTarget());

// Throws Error naming the first field out of range: the kernel's ranges through
// glint::validateGlintParameters (one place for them), uv_scale > 0, both ends of
// log_density_range within log_density's range, texture indices below textureCount (or -1).
void validateGlintLayer(const GlintLayer& layer, std::size_t textureCount);

// The default log density of a glint layer that a material gets without parameters of its own
// (applyGlint): the density at which the layer shows about kVisibleGlintMicrofacetsPerPixel
// microfacets per pixel where its surface faces the scene's "default" camera, in a frame of
// kVisibleGlintFrameSize pixels high (the commands' default size). Microfacets per pixel are
// e^D * (uv area per square metre) * (pixel side in metres)^2, so
//   D = ln(kVisibleGlintMicrofacetsPerPixel / (uvAreaPerSquareMetre * pixelSide^2)),
// rounded to 0.1 (the printed value is the one used) and kept within the accepted range. The uv
// area per square metre is that of the meshes using the material: the sum of their triangles'
// uv areas over the sum of their world areas. The pixel side is 2 d tan(fov / 2) / 512 at the
// distance d from the camera to the area-weighted centre of those triangles (2 h / 512 for an
// orthographic camera of half height h). The 100 lies within the built-in scenes' own glint
// layers, 4 to 25,000 at their default cameras (docs/scenes.md, "Default glint density").
inline constexpr double kVisibleGlintMicrofacetsPerPixel = 100.0;
inline constexpr int kVisibleGlintFrameSize = 512;
struct VisibleGlintDensity {
  bool hasUvArea = false;             // false: no triangle with uv area (and world area) uses it
  double uvAreaPerSquareMetre = 0.0;  // mesh uv units^2 per m^2
  double pixelSide = 0.0;             // metres, at the material's centre
  float logDensity = GlintLayer{}.logDensity;  // GlintLayer's default where there is no uv area
};
VisibleGlintDensity visibleGlintDensity(const Scene& scene, int material);

// Puts a glint layer on every material named in `materialNames` that has none ("*" names them
// all): the material's roughness as alpha (alphaFromRoughness), the log density of
// visibleGlintDensity, GlintLayer's defaults for the rest. A material that already has a layer
// (EXT_materials_glint or extras.glint) keeps it: its own parameters win. Throws Error, listing
// the scene's material names, for a name that no material has. Several materials with the same name all get the
// layer. Returns the indices of the materials that got a new layer, in order.
std::vector<std::size_t> applyGlint(Scene& scene, const std::vector<std::string>& materialNames);

// Named views of the bounding box [low, high]: "front" looks at its centre from +z, far enough that
// the bounding sphere fits the 45 degree vertical field of view with a 10% margin; "side" from +x,
// "top" from +y (up = -z), "close" from +z at half that distance; "default" is "front", or "top" or
// "side" for a model flat along y or x, which the front sees edge-on.
std::map<std::string, Camera> standardCameras(glm::vec3 low, glm::vec3 high);
// The same view (position, target, up, projection and its angle or height), whoever made it.
bool sameView(const Camera& a, const Camera& b);

// Lighting for a scene that brings none: a point light above, right and in front of the bounding
// box, a directional light from the upper left, and a uniform grey-blue environment (0.3), scaled
// so that a white diffuse surface facing the lights is about as bright as 1. Sets defaultLights.
void addDefaultLighting(Scene& scene);

}  // namespace glint::scene
