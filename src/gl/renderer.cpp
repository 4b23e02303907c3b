#include "gl/renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/dictionary_texture.h"
#include "gl/environment.h"
#include "gl/shader.h"
#include "gl/shadow_maps.h"
#include "glint/error.h"
#include "glint/image_io.h"
#include "scene/environment_map.h"
#include "scene/normal_map_moments.h"

namespace glint::gl {

namespace {

// A texture's KHR_texture_transform as the shaders take it: uv' = M * vec3(uv, 1).
void setUvTransform(const ShaderProgram& program, const char* name, const scene::UvTransform& transform) {
  const glm::mat3x2 matrix = transform.matrix();
  glUniformMatrix3x2fv(program.uniform(name), 1, GL_FALSE, &matrix[0][0]);
}

struct GpuMesh {
  GLuint vertexArray = 0;
  GLuint vertexBuffer = 0;
  GLuint indexBuffer = 0;
  GLsizei indexCount = 0;
  int material = 0;
  bool vertexColours = false;  // some vertex's COLOR_0 is not white
};

GLuint makeTexture(int width, int height, GLenum internalFormat, GLenum format, GLenum type, const void* pixels,
                   bool mipmaps, bool repeat) {
  GLuint texture = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &texture);
  const int levels = mipmaps ? 1 + static_cast<int>(std::floor(std::log2(std::max(width, height)))) : 1;
  glTextureStorage2D(texture, levels, internalFormat, width, height);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(texture, 0, 0, 0, width, height, format, type, pixels);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  if (mipmaps) glGenerateTextureMipmap(texture);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, mipmaps ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, repeat ? GL_REPEAT : GL_CLAMP_TO_EDGE);
  return texture;
}

// A glTF sampler's wrap modes and filters on a texture made with its mip chain (makeTexture).
void applySampler(GLuint texture, const scene::TextureSampler& sampler) {
  auto wrap = [](scene::TextureSampler::Wrap mode) {
    return mode == scene::TextureSampler::Wrap::ClampToEdge      ? GL_CLAMP_TO_EDGE
           : mode == scene::TextureSampler::Wrap::MirroredRepeat ? GL_MIRRORED_REPEAT
                                                                 : GL_REPEAT;
  };
  const bool nearest = sampler.minifyNearest;
  const GLint minify = sampler.mipmap == scene::TextureSampler::Mipmap::None ? (nearest ? GL_NEAREST : GL_LINEAR)
                       : sampler.mipmap == scene::TextureSampler::Mipmap::Nearest
                           ? (nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_NEAREST)
                           : (nearest ? GL_NEAREST_MIPMAP_LINEAR : GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, minify);
  glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, sampler.magnifyNearest ? GL_NEAREST : GL_LINEAR);
  glTextureParameteri(texture, GL_TEXTURE_WRAP_S, wrap(sampler.wrapS));
  glTextureParameteri(texture, GL_TEXTURE_WRAP_T, wrap(sampler.wrapT));
}

// Half the texture along each side longer than `limit` (a 2-texel box; the last texel repeats for
// odd sizes), colour textures averaged in linear light as OpenGL filters sRGB textures.
scene::Texture halvedBeyond(const scene::Texture& t, int limit) {
  const int fx = t.width > limit ? 2 : 1;
  const int fy = t.height > limit ? 2 : 1;
  scene::Texture half = t;
  half.width = std::max(1, t.width / fx);
  half.height = std::max(1, t.height / fy);
  half.rgba.assign(static_cast<std::size_t>(half.width) * half.height * 4, 0);
  for (int y = 0; y < half.height; ++y) {
    for (int x = 0; x < half.width; ++x) {
      for (int c = 0; c < 4; ++c) {
        float sum = 0.0f;
        for (int dy = 0; dy < fy; ++dy) {
          for (int dx = 0; dx < fx; ++dx) {
            const int sx = std::min(x * fx + dx, t.width - 1);
            const int sy = std::min(y * fy + dy, t.height - 1);
            const float v = t.rgba[4 * (static_cast<std::size_t>(sy) * t.width + sx) + static_cast<std::size_t>(c)] / 255.0f;
            sum += t.srgb && c < 3 ? srgbToLinear(v) : v;
          }
        }
        const float mean = sum / static_cast<float>(fx * fy);
        half.rgba[4 * (static_cast<std::size_t>(y) * half.width + x) + static_cast<std::size_t>(c)] =
            t.srgb && c < 3 ? linearToSrgb8(mean) : static_cast<std::uint8_t>(std::lround(mean * 255.0f));
      }
    }
  }
  return half;
}

}  // namespace

std::vector<AntiAliasing> allAntiAliasingModes() {
  return {AntiAliasing::None, AntiAliasing::Ggaa, AntiAliasing::GgaaLean};
}

AntiAliasing antiAliasingFromString(const std::string& name) {
  if (name == "none") return AntiAliasing::None;
  if (name == "ggaa") return AntiAliasing::Ggaa;
  if (name == "ggaa+lean") return AntiAliasing::GgaaLean;
  throw Error("unknown anti-aliasing '" + name + "' (choices: none, ggaa, ggaa+lean)");
}

const char* toString(AntiAliasing mode) {
  switch (mode) {
    case AntiAliasing::None: return "none";
    case AntiAliasing::Ggaa: return "ggaa";
    case AntiAliasing::GgaaLean: return "ggaa+lean";
  }
  return "unknown";
}

const std::vector<QualityPreset>& qualityPresets() {
  // The values and why: docs/benchmarks.md, "Cost tiers".
  static const std::vector<QualityPreset> presets = {
      {"low", "aniso=2,cells=12,drop=0.9", AntiAliasing::None, 1},
      {"medium", "cells=24", AntiAliasing::GgaaLean, 2},
      {"high", "drop=0.1", AntiAliasing::GgaaLean, 2},
      {"exact", "exact", AntiAliasing::GgaaLean, kShadowCascades},
  };
  return presets;
}

const QualityPreset& qualityPreset(const std::string& name) {
  std::string choices;
  for (const QualityPreset& preset : qualityPresets()) {
    if (name == preset.name) return preset;
    choices += (choices.empty() ? "" : ", ") + std::string(preset.name);
  }
  throw Error("unknown quality '" + name + "' (choices: " + choices + ")");
}

glm::vec2 supersampleJitter(int k) {
  if (k == 0) return glm::vec2(0.0f);
  // R2: the fractional parts of k / g and k / g^2, g the plastic number.
  constexpr double g = 1.32471795724474602596;
  const double x = std::fmod(0.5 + k / g, 1.0);
  const double y = std::fmod(0.5 + k / (g * g), 1.0);
  return glm::vec2(static_cast<float>(x - 0.5), static_cast<float>(y - 0.5));
}

glm::mat4 viewProjection(const scene::Camera& camera, int width, int height, glm::vec2 jitter, glm::vec3 boundsMin,
                         glm::vec3 boundsMax) {
  const glm::vec3 centre = 0.5f * (boundsMin + boundsMax);
  const float radius = std::max(0.5f * glm::length(boundsMax - boundsMin), 1e-3f);
  const float distance = glm::length(centre - camera.position);
  const float farPlane = distance + 2.0f * radius;
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  // A translation in normalised device coordinates: 2 / size per pixel.
  const glm::vec2 jitterNdc = 2.0f * jitter / glm::vec2(width, height);
  glm::mat4 projection;
  if (camera.projection == scene::Camera::Projection::Orthographic) {
    // Depth is linear here, so the near plane can be the camera's own: the path tracer's rays
    // start there too. The translation goes in the column that w = 1 multiplies.
    const float h = camera.orthographicHalfHeight;
    projection = glm::ortho(-h * aspect, h * aspect, -h, h, 0.0f, farPlane);
    projection[3][0] += jitterNdc.x;
    projection[3][1] += jitterNdc.y;
  } else {
    const float nearPlane = std::max(farPlane * 1e-4f, (distance - radius) * 0.5f);
    projection = glm::perspective(glm::radians(camera.verticalFovDegrees), aspect, nearPlane, farPlane);
    // Clip w is the view depth: the translation goes in the column that z multiplies.
    projection[2][0] += jitterNdc.x;
    projection[2][1] += jitterNdc.y;
  }
  return projection * glm::lookAt(camera.position, camera.target, camera.up);
}

// The forward program of a specular model (shaders/forward.frag, SPECULAR_MODEL), for materials
// with or without coloured glints (GLINT_COLOURED_CELLS), for the scene's number of lights
// (LIGHT_COUNT). The colour is a compile-time switch, not a uniform: llvmpipe runs both sides of
// every branch for all pixels, so a uniform flag made every glint material pay for the colour
// (15% of the glint shader's instructions when it was a second hash and a hue). So are the glTF
// features most meshes do not use: texture transforms cost 14% of a Cook-Torrance frame's
// instructions and vertex colours 2% where every pixel paid for them (docs/benchmarks.md, "What made it fast, and why").
struct ForwardVariant {
  SpecularModel model;
  bool colouredCells;
  bool filtered;   // GLINT_FILTERED: glint programs that anti-alias (AntiAliasing::Ggaa, GgaaLean)
  bool lean;       // GLINT_LEAN: and filter their normal map (AntiAliasing::GgaaLean)
  bool normalMapFinest;  // NORMAL_MAP_FINEST: the normal map at its finest level
  int lightCount;  // LIGHT_COUNT: glint programs walk a footprint's cells once for all the lights
  int regionCount;  // REGION_COUNT: the environment's regions drawn analytically (glints in glint programs)
  int areaLightCount;  // AREA_LIGHT_COUNT: the scene's emissive rectangles drawn as lights, likewise
  bool alphaMask;  // ALPHA_MASK: glTF alphaMode MASK (a discard, kept out of every other program)
  bool textureTransforms;  // TEXTURE_TRANSFORMS: some texture of the material has a KHR_texture_transform
  bool vertexColours;      // VERTEX_COLOURS: the mesh has COLOR_0 other than white
  // GLINT_NDF, GLINT_MASKING, GLINT_MULTIPLE_SCATTERING: the material's specular target
  // (scene::Material::specular), compiled in so that the paper's Beckmann with V-cavity pays
  // nothing for the others.
  int ndf;
  int masking;
  bool multipleScattering;
  bool shadows;     // SHADOWS: the lights cast shadows (shaders/shadows.glsl)
  int shadowCubes;  // SHADOW_CUBES: bit i, light i's shadow map is a cube
  bool centroid;    // CENTROID_SHADING: several samples a pixel, edges shaded inside the surface
  // GLINT_FOOTPRINT_POLICY: the words of the glint footprint policy (bits: 1 aniso, 2 cells, 4 drop;
  // glintPixelFootprint), compiled in so that each policy pays for its own words only and exact for
  // none; their values come from uGlintFootprintPolicy.
  int footprintWords;
  // GLINT_LOD_CONSTRUCTION: the LOD construction of the material's glint layer (kernel/glint_lod.h,
  // glintLodCell), compiled in so that the paper's pays nothing for the others.
  int lodConstruction;
  bool clearcoat;  // CLEARCOAT: the material has a KHR_materials_clearcoat coat (kernel/clearcoat.h)
  bool clearcoatTextures;  // CLEARCOAT_TEXTURES: and the coat has textures (their samplers only then)
  auto operator<=>(const ForwardVariant&) const = default;
};

ShaderProgram forwardProgram(ForwardVariant variant) {
  const char* specular = variant.model == SpecularModel::Glint          ? "SPECULAR_GLINT"
                         : variant.model == SpecularModel::CookTorrance ? "SPECULAR_COOK_TORRANCE"
                         : variant.model == SpecularModel::ZirrKaplanyan ? "SPECULAR_ZIRR_KAPLANYAN"
                                                                     : "SPECULAR_ZIRR_KAPLANYAN_REFERENCE";
  return ShaderProgram({{GL_VERTEX_SHADER, "forward.vert"}, {GL_FRAGMENT_SHADER, "forward.frag"}},
                       {{"SPECULAR_MODEL", specular},
                        {"GLINT_COLOURED_CELLS", variant.colouredCells ? "1" : "0"},
                        {"GLINT_FILTERED", variant.filtered ? "1" : "0"},
                        {"GLINT_LEAN", variant.lean ? "1" : "0"},
                        {"NORMAL_MAP_FINEST", variant.normalMapFinest ? "1" : "0"},
                        {"LIGHT_COUNT", std::to_string(variant.lightCount)},
                        {"REGION_COUNT", std::to_string(variant.regionCount)},
                        {"AREA_LIGHT_COUNT", std::to_string(variant.areaLightCount)},
                        {"ALPHA_MASK", variant.alphaMask ? "1" : "0"},
                        {"TEXTURE_TRANSFORMS", variant.textureTransforms ? "1" : "0"},
                        {"VERTEX_COLOURS", variant.vertexColours ? "1" : "0"},
                        {"GLINT_NDF", std::to_string(variant.ndf)},
                        {"GLINT_MASKING", std::to_string(variant.masking)},
                        {"GLINT_MULTIPLE_SCATTERING", variant.multipleScattering ? "1" : "0"},
                        {"SHADOWS", variant.shadows ? "1" : "0"},
                        {"SHADOW_CUBES", std::to_string(variant.shadowCubes)},
                        {"SHADOW_CASCADES", std::to_string(kShadowCascades)},
                        {"SHADOW_CASCADE_MARGIN", std::to_string(kCascadeMarginTexels)},
                        {"CENTROID_SHADING", variant.centroid ? "1" : "0"},
                        {"GLINT_FOOTPRINT_POLICY", std::to_string(variant.footprintWords)},
                        {"GLINT_LOD_CONSTRUCTION", std::to_string(variant.lodConstruction)},
                        {"CLEARCOAT", variant.clearcoat ? "1" : "0"},
                        {"CLEARCOAT_TEXTURES", variant.clearcoatTextures ? "1" : "0"}});
}

// The depth pre-pass's program; with alphaMask, it drops the fragments that alphaMode MASK cuts
// out. The plain one has no discard, so the rasteriser can test and write depth before shading.
// With linearDepth, the shadow maps' (shadow_maps.h): depth is the distance from a light.
ShaderProgram depthPrepassProgram(bool alphaMask, bool linearDepth) {
  return ShaderProgram({{GL_VERTEX_SHADER, "forward.vert"}, {GL_FRAGMENT_SHADER, "depth_prepass.frag"}},
                       {{"ALPHA_MASK", alphaMask ? "1" : "0"}, {"LINEAR_DEPTH", linearDepth ? "1" : "0"}});
}

bool isMasked(const scene::Material& material) { return material.alphaMode == scene::Material::AlphaMode::Mask; }

// The words a footprint policy uses, as GLINT_FOOTPRINT_POLICY's bits.
int footprintWords(const kernel::GlintFootprintPolicy& policy) {
  return (policy.maxAnisotropy > 0.0f ? 1 : 0) | (policy.maxCells > 0.0f ? 2 : 0) | (policy.minBlend > 0.0f ? 4 : 0);
}

// The program a material is drawn with. A material without a glint layer is Cook-Torrance under
// every BRDF, so it gets the Cook-Torrance program: llvmpipe runs both sides of a branch, and the
// glint (or Zirr & Kaplanyan) program would make it pay for the other lobe's setup as well.
ForwardVariant forwardVariant(const FrameSettings& settings, const scene::Material& material, const GpuMesh& mesh,
                              int lightCount, int regionCount, int areaLightCount, int shadowCubes) {
  const SpecularModel model = material.glint.enabled ? settings.brdf : SpecularModel::CookTorrance;
  const bool coloured = model == SpecularModel::Glint && material.glint.colouredCells;
  const bool filtered = model == SpecularModel::Glint && settings.antiAliasing != AntiAliasing::None;
  const bool normalMap = material.normalTexture >= 0;
  const bool lean = filtered && normalMap && settings.antiAliasing == AntiAliasing::GgaaLean;
  const bool finest = normalMap && !lean && settings.normalMapFinestLevel;
  const bool transforms = !(material.baseColourUv.identity() && material.metallicRoughnessUv.identity() &&
                            material.normalUv.identity() && material.occlusionUv.identity() &&
                            material.emissiveUv.identity() && material.clearcoat.uv.identity() &&
                            material.clearcoat.roughnessUv.identity() && material.clearcoat.normalUv.identity());
  return ForwardVariant{model,
                        coloured,
                        filtered,
                        lean,
                        finest,
                        lightCount,
                        regionCount,
                        areaLightCount,
                        isMasked(material),
                        transforms,
                        mesh.vertexColours,
                        material.specular.ndf,
                        material.specular.masking,
                        material.specular.multipleScattering,
                        settings.shadows && lightCount + areaLightCount > 0,
                        settings.shadows ? shadowCubes : 0,
                        settings.msaa > 1,
                        model == SpecularModel::Glint ? footprintWords(settings.footprintPolicy) : 0,
                        model == SpecularModel::Glint ? material.glint.lod : kernel::GLINT_LOD_PAPER,
                        material.clearcoat.enabled(),
                        material.clearcoat.enabled() && material.clearcoat.hasTextures()};
}

// The renderer's uniform buffer of every material's glint layer (kernel::GlintMaterial, std140),
// one after the other at the stride the OpenGL's uniform-buffer offset alignment allows, so that a
// mesh's draw binds its material's range (glBindBufferRange) instead of setting uniforms by name.
// Made with the renderer; a material the viewer edits between frames is written again.
class GlintMaterialBuffer {
 public:
  GlintMaterialBuffer() = default;
  GlintMaterialBuffer(const GlintMaterialBuffer&) = delete;
  GlintMaterialBuffer& operator=(const GlintMaterialBuffer&) = delete;
  ~GlintMaterialBuffer() { glDeleteBuffers(1, &buffer_); }

  // Writes the materials' layers that differ from those written last (all on the first call).
  void update(const std::vector<scene::Material>& materials) {
    std::vector<kernel::GlintMaterial> packed;
    packed.reserve(materials.size());
    for (const scene::Material& m : materials) packed.push_back(scene::glintMaterial(m.glint, m.specular));
    if (packed.size() != written_.size() || !buffer_) create(packed);
    for (std::size_t i = 0; i < packed.size(); ++i) {
      if (std::memcmp(&packed[i], &written_[i], sizeof(kernel::GlintMaterial)) == 0) continue;
      glNamedBufferSubData(buffer_, static_cast<GLintptr>(i) * stride_, sizeof(kernel::GlintMaterial), &packed[i]);
      written_[i] = packed[i];
    }
  }

  // Binds material `index`'s layer to the forward shader's block.
  void bind(int index) const {
    glBindBufferRange(GL_UNIFORM_BUFFER, kGlintMaterialBinding, buffer_, static_cast<GLintptr>(index) * stride_,
                      sizeof(kernel::GlintMaterial));
  }

 private:
  void create(const std::vector<kernel::GlintMaterial>& packed) {
    glDeleteBuffers(1, &buffer_);
    GLint alignment = 1;
    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
    const GLintptr size = sizeof(kernel::GlintMaterial);
    stride_ = (size + alignment - 1) / alignment * alignment;
    std::vector<std::uint8_t> bytes(std::max<std::size_t>(packed.size(), 1) * static_cast<std::size_t>(stride_), 0);
    for (std::size_t i = 0; i < packed.size(); ++i) {
      std::memcpy(bytes.data() + i * static_cast<std::size_t>(stride_), &packed[i], sizeof(kernel::GlintMaterial));
    }
    glCreateBuffers(1, &buffer_);
    glNamedBufferStorage(buffer_, static_cast<GLsizeiptr>(bytes.size()), bytes.data(), GL_DYNAMIC_STORAGE_BIT);
    written_ = packed;
  }

  GLuint buffer_ = 0;
  GLintptr stride_ = 0;
  std::vector<kernel::GlintMaterial> written_;
};

struct Renderer::Gpu {
  std::map<ForwardVariant, ShaderProgram> forward;  // compiled on first use
  std::unique_ptr<ShaderProgram> background;        // likewise
  // Likewise; [alphaMode MASK + 2 * linear depth (the shadow maps of positional lights)].
  std::array<std::unique_ptr<ShaderProgram>, 4> depthPrepass;
  ShadowMaps shadowMaps;
  GLuint emptyVertexArray = 0;                      // the background's triangle has no attributes
  std::unique_ptr<DictionaryTexture> dictionary;
  GlintMaterialBuffer glintMaterials;
  std::vector<GpuMesh> meshes;
  std::vector<GLuint> textures;
  // Per material with a normal map, its slope moments (scene/normal_map_moments.h), made on first use.
  std::map<int, std::array<GLuint, 2>> leanMoments;
  GLuint white = 0;
  GLuint flatNormal = 0;
  GLuint environment = 0;            // without the regions drawn as lights (Renderer::environmentLights)
  GLuint backgroundEnvironment = 0;  // the whole map, seen behind the meshes; `environment` when no region was taken
  float environmentMaxLod = 0.0f;
  std::array<glm::vec3, 9> irradiance{};
  GLuint framebuffer = 0;
  GLuint radiance = 0;
  GLuint depth = 0;
  // With several samples a pixel, the frame is drawn into these and resolved into `radiance`.
  GLuint multisampleFramebuffer = 0;
  GLuint multisampleRadiance = 0;
  GLuint multisampleDepth = 0;
  int width = 0;
  int height = 0;
  int samples = 1;

  ~Gpu() {
    for (const GpuMesh& m : meshes) {
      glDeleteVertexArrays(1, &m.vertexArray);
      glDeleteBuffers(1, &m.vertexBuffer);
      glDeleteBuffers(1, &m.indexBuffer);
    }
    glDeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
    for (const auto& [material, moments] : leanMoments) glDeleteTextures(2, moments.data());
    glDeleteTextures(1, &white);
    glDeleteTextures(1, &flatNormal);
    if (backgroundEnvironment != environment) glDeleteTextures(1, &backgroundEnvironment);
    glDeleteTextures(1, &environment);
    glDeleteVertexArrays(1, &emptyVertexArray);
    releaseTarget();
  }

  void releaseTarget() {
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &radiance);
    glDeleteRenderbuffers(1, &depth);
    glDeleteFramebuffers(1, &multisampleFramebuffer);
    glDeleteRenderbuffers(1, &multisampleRadiance);
    glDeleteRenderbuffers(1, &multisampleDepth);
    framebuffer = radiance = depth = multisampleFramebuffer = multisampleRadiance = multisampleDepth = 0;
  }

  // The framebuffer a frame is drawn into: `framebuffer` at one sample a pixel.
  GLuint drawFramebuffer() const { return samples > 1 ? multisampleFramebuffer : framebuffer; }

  void resizeTarget(int w, int h, int s) {
    if (w == width && h == height && s == samples && framebuffer) return;
    releaseTarget();
    width = w;
    height = h;
    samples = s;
    glCreateTextures(GL_TEXTURE_2D, 1, &radiance);
    glTextureStorage2D(radiance, 1, GL_RGBA32F, w, h);
    glTextureParameteri(radiance, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(radiance, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glCreateRenderbuffers(1, &depth);
    glNamedRenderbufferStorage(depth, GL_DEPTH24_STENCIL8, w, h);  // stencil: renderFrame's shading pass
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, radiance, 0);
    glNamedFramebufferRenderbuffer(framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth);
    if (glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw Error("OpenGL: cannot make a " + std::to_string(w) + "x" + std::to_string(h) + " RGBA32F render target");
    }
    if (s == 1) return;
    glCreateRenderbuffers(1, &multisampleRadiance);
    glNamedRenderbufferStorageMultisample(multisampleRadiance, s, GL_RGBA32F, w, h);
    glCreateRenderbuffers(1, &multisampleDepth);
    glNamedRenderbufferStorageMultisample(multisampleDepth, s, GL_DEPTH24_STENCIL8, w, h);
    glCreateFramebuffers(1, &multisampleFramebuffer);
    glNamedFramebufferRenderbuffer(multisampleFramebuffer, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, multisampleRadiance);
    glNamedFramebufferRenderbuffer(multisampleFramebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, multisampleDepth);
    if (glCheckNamedFramebufferStatus(multisampleFramebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw Error("OpenGL: cannot make a " + std::to_string(w) + "x" + std::to_string(h) + " RGBA32F render target of " +
                  std::to_string(s) + " samples a pixel");
    }
  }
};

Renderer::Renderer(const scene::Scene& scene, const Dictionary& dictionary)
    : scene_(scene), materials_(scene.materials), lights_(scene.lights), gpu_(std::make_unique<Gpu>()) {
  Gpu& g = *gpu_;
  g.dictionary = std::make_unique<DictionaryTexture>(dictionary);
  g.glintMaterials.update(materials_);
  const std::uint8_t white[4] = {255, 255, 255, 255};
  // The flat normal (0, 0, 1) exactly: 8-bit 128 would decode to 0.0039 and tilt every normal
  // of a material without a normal map by 0.32 degrees.
  const float flat[4] = {0.5f, 0.5f, 1.0f, 1.0f};
  g.white = makeTexture(1, 1, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, white, false, true);
  g.flatNormal = makeTexture(1, 1, GL_RGBA32F, GL_RGBA, GL_FLOAT, flat, false, true);
  GLint maxTextureSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxTextureSize);
  for (const scene::Texture& source : scene.textures) {
    // A texture beyond this OpenGL's size limit would draw black: it is halved until it fits, and
    // said once (the path tracer keeps it whole).
    scene::Texture fitted;
    const scene::Texture* t = &source;
    while (t->width > maxTextureSize || t->height > maxTextureSize) {
      fitted = halvedBeyond(*t, maxTextureSize);
      t = &fitted;
    }
    if (t != &source) {
      warnings_.push_back("texture '" + source.name + "' (" + std::to_string(source.width) + "x" +
                          std::to_string(source.height) + ") exceeds this OpenGL's limit of " +
                          std::to_string(maxTextureSize) + " texels a side; the rasteriser draws it at " +
                          std::to_string(t->width) + "x" + std::to_string(t->height));
    }
    g.textures.push_back(makeTexture(t->width, t->height, t->srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, GL_RGBA,
                                     GL_UNSIGNED_BYTE, t->rgba.data(), true, true));
    applySampler(g.textures.back(), source.sampler);
  }
  const scene::Environment& env = scene.environment;
  // The map's brightest small regions become directional lights, so that glints see them; the
  // forward pass's prefiltered specular and irradiance take the rest, the background the whole map.
  const int freeLightSlots = std::max(0, kMaxLights - static_cast<int>(lights_.size()));
  scene::EnvironmentLights split = scene::extractEnvironmentLights(env, std::min(env.rasterLights, freeLightSlots));
  environmentLights_ = std::move(split.lights);
  scene::EnvironmentRegions regions =
      scene::environmentGlintRegions(split.residual, std::min(env.rasterRegions, kMaxEnvironmentRegions));
  environmentRegions_ = std::move(regions.regions);
  scene::AreaLights area = scene::findAreaLights(scene);
  for (const std::string& skipped : area.skipped) warnings_.push_back(skipped + ": it glows but lights nothing in the rasteriser");
  if (area.lights.size() > static_cast<std::size_t>(kMaxAreaLights)) {
    warnings_.push_back("the rasteriser draws " + std::to_string(kMaxAreaLights) + " of the scene's " +
                        std::to_string(area.lights.size()) + " area lights, the brightest (radiance times area)");
    std::sort(area.lights.begin(), area.lights.end(), [](const scene::AreaLight& a, const scene::AreaLight& b) {
      return scene::luminance(a.radiance) * a.area() > scene::luminance(b.radiance) * b.area();
    });
    area.lights.resize(kMaxAreaLights);
  }
  areaLights_ = std::move(area.lights);
  auto uploadEnvironment = [](const scene::Environment& e) {
    if (!e.pixels.empty()) return makeTexture(e.width, e.height, GL_RGBA32F, GL_RGB, GL_FLOAT, e.pixels.data(), true, true);
    const glm::vec3 uniform[4] = {e.uniform, e.uniform, e.uniform, e.uniform};
    return makeTexture(2, 2, GL_RGBA32F, GL_RGB, GL_FLOAT, uniform, false, true);
  };
  // The prefiltered specular and the irradiance lack the regions too (drawn analytically, both lobes).
  g.environment = uploadEnvironment(regions.residual);
  g.backgroundEnvironment = environmentLights_.empty() && environmentRegions_.empty() ? g.environment : uploadEnvironment(env);
  if (!env.pixels.empty()) g.environmentMaxLod = std::floor(std::log2(static_cast<float>(std::max(env.width, env.height))));
  g.irradiance = irradianceSh(regions.residual);
  for (const scene::Mesh& mesh : scene.meshes) {
    GpuMesh m;
    m.material = mesh.material;
    m.indexCount = static_cast<GLsizei>(mesh.indices.size());
    m.vertexColours = std::any_of(mesh.vertices.begin(), mesh.vertices.end(),
                                  [](const scene::Vertex& v) { return v.colour != glm::vec4(1.0f); });
    glCreateBuffers(1, &m.vertexBuffer);
    glNamedBufferStorage(m.vertexBuffer, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(scene::Vertex)),
                         mesh.vertices.data(), 0);
    glCreateBuffers(1, &m.indexBuffer);
    glNamedBufferStorage(m.indexBuffer, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                         mesh.indices.data(), 0);
    glCreateVertexArrays(1, &m.vertexArray);
    glVertexArrayVertexBuffer(m.vertexArray, 0, m.vertexBuffer, 0, sizeof(scene::Vertex));
    glVertexArrayElementBuffer(m.vertexArray, m.indexBuffer);
    const struct {
      GLuint location;
      GLint size;
      GLuint offset;
    } attributes[] = {{0, 3, offsetof(scene::Vertex, position)},
                      {1, 3, offsetof(scene::Vertex, normal)},
                      {2, 4, offsetof(scene::Vertex, tangent)},
                      {3, 2, offsetof(scene::Vertex, uv)},
                      {4, 4, offsetof(scene::Vertex, colour)}};
    for (const auto& a : attributes) {
      glEnableVertexArrayAttrib(m.vertexArray, a.location);
      glVertexArrayAttribFormat(m.vertexArray, a.location, a.size, GL_FLOAT, GL_FALSE, a.offset);
      glVertexArrayAttribBinding(m.vertexArray, a.location, 0);
    }
    g.meshes.push_back(m);
  }
}

Renderer::~Renderer() = default;

GLuint Renderer::radianceTexture() const { return gpu_->radiance; }

int Renderer::maxMsaaSamples() const {
  // The renderbuffer's own limit: RGBA32F may allow fewer samples than GL_MAX_SAMPLES.
  GLint samples = 1;
  glGetInternalformativ(GL_RENDERBUFFER, GL_RGBA32F, GL_SAMPLES, 1, &samples);
  GLint maxSamples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &maxSamples);
  int powerOfTwo = 1;
  while (2 * powerOfTwo <= std::min(samples, maxSamples)) powerOfTwo *= 2;
  return powerOfTwo;
}

// One frame's state, shared by its passes: the projection, the lights as the shaders take them,
// the shadow maps' lookups.
struct Renderer::FrameState {
  glm::mat4 projection{1.0f};
  GLuint target = 0;
  // The scene's lights, then those taken out of the environment map; both cast shadows.
  std::vector<scene::Light> lights;
  int lightCount = 0;
  glm::vec4 lightPositions[kMaxLights];  // w = 1: point or spot at xyz; w = 0: unit direction towards the light
  glm::vec3 lightIntensities[kMaxLights];
  glm::vec3 spotAxes[kMaxLights];
  glm::vec2 spotCones[kMaxLights];
  float inverseRanges[kMaxLights] = {};
  // The environment's glint regions: four corners each (unit directions), and their radiance.
  int regionCount = 0;
  glm::vec3 regionCorners[4 * kMaxEnvironmentRegions];
  glm::vec3 regionRadiances[kMaxEnvironmentRegions];
  // The area lights: four corners each (world positions), radiance, and whether both faces emit.
  int areaLightCount = 0;
  glm::vec3 areaLightCorners[4 * kMaxAreaLights];
  glm::vec3 areaLightRadiances[kMaxAreaLights];
  int areaLightTwoSided[kMaxAreaLights];
  // The shadows' casters: the lights, then the area lights (shadows.glsl).
  bool shadows = false;
  int shadowEntries = 0;  // (lightCount + areaLightCount) * kShadowCascades
  int shadowCubes = 0;    // bit i: caster i has a cube map
  glm::mat4 shadowMatrices[(kMaxLights + kMaxAreaLights) * kShadowCascades];
  float shadowLayers[(kMaxLights + kMaxAreaLights) * kShadowCascades] = {};
  float shadowDepthScales[(kMaxLights + kMaxAreaLights) * kShadowCascades] = {};
  float shadowTexels[(kMaxLights + kMaxAreaLights) * kShadowCascades] = {};
};

void Renderer::renderFrame(const FrameSettings& settings) {
  FrameState frame = beginFrame(settings);
  shadowPass(settings, frame);
  depthPrepass(frame);
  shadingPass(settings, frame);
  backgroundPass(frame);
  resolve(settings);
}

GLuint Renderer::textureOr(int index, GLuint fallback) const {
  const Gpu& g = *gpu_;
  return index >= 0 && index < static_cast<int>(g.textures.size()) ? g.textures[static_cast<std::size_t>(index)] : fallback;
}

// glTF: back faces of single-sided materials are culled; double-sided ones (curtains) are drawn
// from both sides.
void Renderer::setCulling(int material) const {
  if (materials_[static_cast<std::size_t>(material)].doubleSided) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
  }
}

// The frame's checks, its target cleared, its projection and its lights.
Renderer::FrameState Renderer::beginFrame(const FrameSettings& settings) {
  Gpu& g = *gpu_;
  if (settings.msaa < 1 || (settings.msaa & (settings.msaa - 1)) != 0 || settings.msaa > maxMsaaSamples()) {
    throw Error("multisampling: " + std::to_string(settings.msaa) + " samples a pixel; this OpenGL takes 1, 2, ... " +
                std::to_string(maxMsaaSamples()) + " (powers of two)");
  }
  if (settings.shadowCascades < 1 || settings.shadowCascades > kShadowCascades) {
    throw Error("shadow cascades: " + std::to_string(settings.shadowCascades) + "; from 1 to " +
                std::to_string(kShadowCascades));
  }
  validateFootprintPolicy(settings.footprintPolicy);
  g.glintMaterials.update(materials_);  // those the viewer edited since the last frame
  g.resizeTarget(settings.width, settings.height, settings.msaa);
  FrameState frame;
  frame.target = g.drawFramebuffer();
  glBindFramebuffer(GL_FRAMEBUFFER, frame.target);
  glViewport(0, 0, settings.width, settings.height);
  glEnable(GL_DEPTH_TEST);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glDisable(GL_BLEND);
  const float clear[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  glClearNamedFramebufferfv(frame.target, GL_COLOR, 0, clear);
  glClearNamedFramebufferfi(frame.target, GL_DEPTH_STENCIL, 0, 1.0f, 0);

  frame.projection = viewProjection(settings.camera, settings.width, settings.height, settings.jitter,
                                    scene_.boundsMin(), scene_.boundsMax());
  frame.lights = lights_;
  frame.lights.insert(frame.lights.end(), environmentLights_.begin(), environmentLights_.end());
  if (frame.lights.size() > static_cast<std::size_t>(kMaxLights)) frame.lights.resize(kMaxLights);
  frame.lightCount = static_cast<int>(frame.lights.size());
  for (int i = 0; i < frame.lightCount; ++i) {
    const scene::Light& light = frame.lights[static_cast<std::size_t>(i)];
    frame.lightPositions[i] = light.positional() ? glm::vec4(light.position, 1.0f)
                                                 : glm::vec4(-glm::normalize(light.direction), 0.0f);
    frame.lightIntensities[i] = light.intensity;
    frame.spotAxes[i] = light.spotAxis();
    frame.spotCones[i] = light.coneScaleOffset();
    frame.inverseRanges[i] = light.inverseRange();
  }
  frame.regionCount = static_cast<int>(environmentRegions_.size());
  for (int r = 0; r < frame.regionCount; ++r) {
    const scene::EnvironmentRegion& region = environmentRegions_[static_cast<std::size_t>(r)];
    for (int k = 0; k < 4; ++k) frame.regionCorners[4 * r + k] = region.corners[static_cast<std::size_t>(k)];
    frame.regionRadiances[r] = region.radiance;
  }
  frame.areaLightCount = static_cast<int>(areaLights_.size());
  for (int a = 0; a < frame.areaLightCount; ++a) {
    const scene::AreaLight& light = areaLights_[static_cast<std::size_t>(a)];
    for (int k = 0; k < 4; ++k) frame.areaLightCorners[4 * a + k] = light.corners[static_cast<std::size_t>(k)];
    frame.areaLightRadiances[a] = light.radiance;
    frame.areaLightTwoSided[a] = light.twoSided ? 1 : 0;
  }
  frame.shadows = settings.shadows && frame.lightCount + frame.areaLightCount > 0;
  frame.shadowEntries = (frame.lightCount + frame.areaLightCount) * kShadowCascades;
  return frame;
}

// Every mesh's depth, alpha masks applied: the pre-pass's (culled as shaded), or a shadow map's
// (both sides: linearDepth for positional lights, shadow_maps.h).
void Renderer::drawDepths(const glm::mat4& viewProjection, bool linearDepth, glm::vec3 origin, float depthScale,
                          bool cull) {
  Gpu& g = *gpu_;
  for (const GpuMesh& mesh : g.meshes) {
    const scene::Material& m = materials_[static_cast<std::size_t>(mesh.material)];
    std::unique_ptr<ShaderProgram>& program = g.depthPrepass[(isMasked(m) ? 1 : 0) + (linearDepth ? 2 : 0)];
    if (!program) program = std::make_unique<ShaderProgram>(depthPrepassProgram(isMasked(m), linearDepth));
    glUseProgram(program->id());
    glUniformMatrix4fv(program->uniform("uViewProjection"), 1, GL_FALSE, &viewProjection[0][0]);
    if (linearDepth) {
      glUniform3fv(program->uniform("uDepthOrigin"), 1, &origin.x);
      glUniform1f(program->uniform("uDepthScale"), depthScale);
    }
    if (isMasked(m)) {
      glUniform4fv(program->uniform("uBaseColour"), 1, &m.baseColour.x);
      setUvTransform(*program, "uBaseColourUv", m.baseColourUv);
      glUniform1f(program->uniform("uAlphaCutoff"), m.alphaCutoff);
      glBindTextureUnit(1, textureOr(m.baseColourTexture, g.white));
    }
    if (cull) setCulling(mesh.material);
    glBindVertexArray(mesh.vertexArray);
    glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
  }
}

// The lights' shadow maps, drawn again only when what they depend on has changed: the lights,
// the alpha masks (the meshes do not move) and, for a directional light's cascades, the camera
// (shadow_maps.h): its frustum without the frame's jitter, so that the jittered frames of one
// image share their maps.
void Renderer::shadowPass(const FrameSettings& settings, FrameState& frame) {
  if (!frame.shadows) return;
  Gpu& g = *gpu_;
  // An area light casts its centre's shadow: a point light's cube map from there. Its own quad lies
  // in a plane through that point, edge-on to every face of the cube, and so hides nothing.
  std::vector<scene::Light> casters = frame.lights;
  for (const scene::AreaLight& area : areaLights_) {
    scene::Light centre;
    centre.type = scene::Light::Type::Point;
    centre.position = area.centre();
    casters.push_back(centre);
  }
  std::vector<float> key;
  for (const scene::Light& l : casters) {
    key.insert(key.end(), {static_cast<float>(l.type), l.position.x, l.position.y, l.position.z, l.direction.x,
                           l.direction.y, l.direction.z, l.outerConeAngle});
  }
  for (const scene::Material& m : materials_) {
    key.insert(key.end(), {static_cast<float>(m.alphaMode), m.alphaCutoff, m.baseColour.a,
                           static_cast<float>(m.baseColourTexture)});
  }
  ShadowView shadowView;
  shadowView.viewProjection = viewProjection(settings.camera, settings.width, settings.height, glm::vec2(0.0f),
                                             scene_.boundsMin(), scene_.boundsMax());
  shadowView.cameraPosition = settings.camera.position;
  shadowView.cascades = settings.shadowCascades;
  g.shadowMaps.update(casters, scene_.boundsMin(), scene_.boundsMax(), shadowView, key,
                      [&](const glm::mat4& viewProjection, bool linearDepth, glm::vec3 origin, float depthScale) {
                        drawDepths(viewProjection, linearDepth, origin, depthScale, false);
                      });
  for (int i = 0; i < frame.shadowEntries; ++i) {
    const ShadowLookup& lookup = g.shadowMaps.lookups()[static_cast<std::size_t>(i)];
    frame.shadowMatrices[i] = lookup.matrix;
    frame.shadowLayers[i] = static_cast<float>(lookup.layer);
    frame.shadowDepthScales[i] = lookup.depthScale;
    frame.shadowTexels[i] = lookup.texel;
  }
  frame.shadowCubes = g.shadowMaps.cubeMask();
  glBindFramebuffer(GL_FRAMEBUFFER, frame.target);
  glViewport(0, 0, settings.width, settings.height);
}

// Depth pre-pass: every mesh's depth first, without colour, so that the shading pass runs the
// forward shader only for the fragment that stays visible in each pixel. Without it every fragment
// that passes the depth test when it is drawn gets shaded, hidden or not, and a glint fragment
// costs several times a Cook-Torrance one (docs/benchmarks.md, "What made it fast, and why").
void Renderer::depthPrepass(const FrameState& frame) {
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  drawDepths(frame.projection, false, glm::vec3(0.0f), 0.0f, true);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

// The frame's uniforms of a forward program: camera, lights, environment, footprint, shadows.
void Renderer::setFrameUniforms(const ShaderProgram& p, const FrameSettings& settings, const FrameState& frame) const {
  const Gpu& g = *gpu_;
  // The point the shaders' view vectors point to, homogeneous: a perspective camera's position, or
  // for an orthographic one the point at infinity up its view axis (every view vector the same).
  const scene::Camera& camera = settings.camera;
  const glm::vec4 cameraPoint = camera.projection == scene::Camera::Projection::Orthographic
                                    ? glm::vec4(glm::normalize(camera.position - camera.target), 0.0f)
                                    : glm::vec4(camera.position, 1.0f);
  const glm::vec2 environmentRotation(std::cos(scene_.environment.rotation), std::sin(scene_.environment.rotation));
  glUseProgram(p.id());
  g.dictionary->bind(p);
  glUniformMatrix4fv(p.uniform("uViewProjection"), 1, GL_FALSE, &frame.projection[0][0]);
  glUniform4fv(p.uniform("uCameraPoint"), 1, &cameraPoint.x);
  glUniform4fv(p.uniform("uLightPosition"), frame.lightCount, &frame.lightPositions[0].x);
  glUniform3fv(p.uniform("uLightIntensity"), frame.lightCount, &frame.lightIntensities[0].x);
  glUniform3fv(p.uniform("uSpotAxis"), frame.lightCount, &frame.spotAxes[0].x);
  glUniform2fv(p.uniform("uSpotCone"), frame.lightCount, &frame.spotCones[0].x);
  glUniform1fv(p.uniform("uLightInverseRange"), frame.lightCount, frame.inverseRanges);
  if (frame.regionCount > 0) {
    glUniform3fv(p.uniform("uRegionCorner"), 4 * frame.regionCount, &frame.regionCorners[0].x);
    glUniform3fv(p.uniform("uRegionRadiance"), frame.regionCount, &frame.regionRadiances[0].x);
  }
  if (frame.areaLightCount > 0) {
    glUniform3fv(p.uniform("uAreaLightCorner"), 4 * frame.areaLightCount, &frame.areaLightCorners[0].x);
    glUniform3fv(p.uniform("uAreaLightRadiance"), frame.areaLightCount, &frame.areaLightRadiances[0].x);
    glUniform1iv(p.uniform("uAreaLightTwoSided"), frame.areaLightCount, frame.areaLightTwoSided);
  }
  glUniform3fv(p.uniform("uIrradianceSh"), 9, &g.irradiance[0].x);
  glUniform1f(p.uniform("uGlintFilterScale"), settings.filterScale);
  glUniform3f(p.uniform("uGlintFootprintPolicy"), settings.footprintPolicy.maxAnisotropy,
              settings.footprintPolicy.maxCells, settings.footprintPolicy.minBlend);
  glUniform1f(p.uniform("uEnvironmentIntensity"), scene_.environment.intensity);
  glUniform1f(p.uniform("uEnvironmentMaxLod"), g.environmentMaxLod);
  glUniform2fv(p.uniform("uEnvironmentRotation"), 1, &environmentRotation.x);
  glBindTextureUnit(9, g.environment);
  if (frame.shadows) {
    g.shadowMaps.bind();
    glUniform1i(p.uniform("uShadowCascades"), g.shadowMaps.cascades());
    glUniformMatrix4fv(p.uniform("uShadowMatrix"), frame.shadowEntries, GL_FALSE, &frame.shadowMatrices[0][0][0]);
    glUniform1fv(p.uniform("uShadowLayer"), frame.shadowEntries, frame.shadowLayers);
    glUniform1fv(p.uniform("uShadowDepthScale"), frame.shadowEntries, frame.shadowDepthScales);
    glUniform1fv(p.uniform("uShadowTexel"), frame.shadowEntries, frame.shadowTexels);
  }
}

// A mesh's material: its uniforms and textures (the glint layer's block bound by range).
void Renderer::bindMaterial(const ShaderProgram& p, int material, bool alphaMask, bool normalMapMoments) {
  Gpu& g = *gpu_;
  const scene::Material& m = materials_[static_cast<std::size_t>(material)];
  const scene::GlintLayer& glint = m.glint;
  glUniform4fv(p.uniform("uBaseColour"), 1, &m.baseColour.x);
  glUniform1f(p.uniform("uMetallic"), m.metallic);
  glUniform1f(p.uniform("uRoughness"), m.roughness);
  glUniform1f(p.uniform("uNormalScale"), m.normalScale);
  glUniform3fv(p.uniform("uEmissive"), 1, &m.emissive.x);
  glUniform1f(p.uniform("uOcclusionStrength"), m.occlusionStrength);
  setUvTransform(p, "uBaseColourUv", m.baseColourUv);
  setUvTransform(p, "uMetallicRoughnessUv", m.metallicRoughnessUv);
  setUvTransform(p, "uNormalUv", m.normalUv);
  setUvTransform(p, "uEmissiveUv", m.emissiveUv);
  setUvTransform(p, "uOcclusionUv", m.occlusionUv);
  if (alphaMask) glUniform1f(p.uniform("uAlphaCutoff"), m.alphaCutoff);
  g.glintMaterials.bind(material);
  glBindTextureUnit(1, textureOr(m.baseColourTexture, g.white));
  glBindTextureUnit(2, textureOr(m.metallicRoughnessTexture, g.white));
  glBindTextureUnit(3, textureOr(m.normalTexture, g.flatNormal));
  glBindTextureUnit(4, textureOr(m.emissiveTexture, g.white));
  glBindTextureUnit(5, textureOr(m.occlusionTexture, g.white));
  glBindTextureUnit(6, textureOr(glint.roughnessTexture, g.white));
  glBindTextureUnit(7, textureOr(glint.logDensityTexture, g.white));
  glBindTextureUnit(8, textureOr(glint.relativeAreaTexture, g.white));
  if (m.clearcoat.enabled()) {
    const scene::Material::Clearcoat& coat = m.clearcoat;
    glUniform2f(p.uniform("uClearcoat"), coat.factor, coat.roughness);
    if (coat.hasTextures()) {
      glUniform1f(p.uniform("uClearcoatNormalScale"), coat.normalScale);
      setUvTransform(p, "uClearcoatUv", coat.uv);
      setUvTransform(p, "uClearcoatRoughnessUv", coat.roughnessUv);
      setUvTransform(p, "uClearcoatNormalUv", coat.normalUv);
      glBindTextureUnit(16, textureOr(coat.texture, g.white));
      glBindTextureUnit(17, textureOr(coat.roughnessTexture, g.white));
      glBindTextureUnit(18, textureOr(coat.normalTexture, g.flatNormal));
    }
  }
  if (normalMapMoments) {
    auto moments = g.leanMoments.find(material);
    if (moments == g.leanMoments.end()) {
      const scene::NormalMapMoments m0 =
          scene::normalMapMoments(scene_.textures[static_cast<std::size_t>(m.normalTexture)], m.normalScale);
      const std::array<GLuint, 2> made = {
          makeTexture(m0.width, m0.height, GL_RGB32F, GL_RGB, GL_FLOAT, m0.first.data(), true, true),
          makeTexture(m0.width, m0.height, GL_RGB32F, GL_RGB, GL_FLOAT, m0.second.data(), true, true)};
      moments = g.leanMoments.emplace(material, made).first;
    }
    glBindTextureUnit(11, moments->second[0]);
    glBindTextureUnit(12, moments->second[1]);
  }
}

// Shading pass: a fragment is shaded where its depth is the one the pre-pass kept and no fragment
// of that pixel has been shaded yet (stencil 0, then 1). Where several fragments share the nearest
// depth the first one drawn wins, as it did under GL_LESS without a pre-pass, so the images are
// those of a single pass, bit for bit. The meshes in the scene's order whatever the BRDF, so that a
// tie in depth goes to the same mesh in every frame; each with its material's program
// (ForwardVariant), switched when it changes, and the frame's uniforms set at each switch.
void Renderer::shadingPass(const FrameSettings& settings, const FrameState& frame) {
  Gpu& g = *gpu_;
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_STENCIL_TEST);
  glStencilFunc(GL_EQUAL, 0, 0xFF);
  glStencilOp(GL_KEEP, GL_KEEP, GL_INCR);
  const ShaderProgram* current = nullptr;
  for (const GpuMesh& mesh : g.meshes) {
    const scene::Material& m = materials_[static_cast<std::size_t>(mesh.material)];
    const ForwardVariant variant = forwardVariant(settings, m, mesh, frame.lightCount, frame.regionCount, frame.areaLightCount, frame.shadowCubes);
    auto program = g.forward.find(variant);
    if (program == g.forward.end()) program = g.forward.emplace(variant, forwardProgram(variant)).first;
    const ShaderProgram& p = program->second;
    if (&p != current) {
      current = &p;
      setFrameUniforms(p, settings, frame);
    }
    bindMaterial(p, mesh.material, variant.alphaMask, variant.lean);
    setCulling(mesh.material);
    glBindVertexArray(mesh.vertexArray);
    glDrawElements(GL_TRIANGLES, mesh.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_CULL_FACE);
}

// The environment where no mesh was drawn (shaders/background.frag): at the far plane, the
// triangle passes the depth test only where the depth is still the cleared 1, so meshes hide it
// before it is shaded.
void Renderer::backgroundPass(const FrameState& frame) {
  Gpu& g = *gpu_;
  if (!g.background) {
    g.background = std::make_unique<ShaderProgram>(
        std::vector<std::pair<GLenum, std::string>>{{GL_VERTEX_SHADER, "fullscreen.vert"},
                                                     {GL_FRAGMENT_SHADER, "background.frag"}},
        std::vector<std::pair<std::string, std::string>>{{"FULLSCREEN_AT_FAR_PLANE", "1"}});
    glCreateVertexArrays(1, &g.emptyVertexArray);
  }
  const ShaderProgram& background = *g.background;
  const glm::mat4 inverseProjection = glm::inverse(frame.projection);
  const glm::vec2 environmentRotation(std::cos(scene_.environment.rotation), std::sin(scene_.environment.rotation));
  glUseProgram(background.id());
  glUniformMatrix4fv(background.uniform("uInverseViewProjection"), 1, GL_FALSE, &inverseProjection[0][0]);
  glUniform1f(background.uniform("uEnvironmentIntensity"), scene_.environment.intensity);
  glUniform1f(background.uniform("uEnvironmentMaxLod"), g.environmentMaxLod);
  glUniform2fv(background.uniform("uEnvironmentRotation"), 1, &environmentRotation.x);
  glBindTextureUnit(9, g.backgroundEnvironment);
  glDepthFunc(GL_LEQUAL);
  glBindVertexArray(g.emptyVertexArray);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  glBindVertexArray(0);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// With several samples a pixel, each pixel the mean of its samples.
void Renderer::resolve(const FrameSettings& settings) {
  if (settings.msaa <= 1) return;
  const Gpu& g = *gpu_;
  glBlitNamedFramebuffer(g.multisampleFramebuffer, g.framebuffer, 0, 0, settings.width, settings.height, 0, 0,
                         settings.width, settings.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

ImageRgbF renderSupersampled(Renderer& renderer, FrameSettings frame, int spp, const std::function<void(int)>& onSample) {
  std::vector<double> sum;
  for (int k = 0; k < spp; ++k) {
    frame.jitter = supersampleJitter(k);
    renderer.renderFrame(frame);
    const std::vector<float> pixels = renderer.readRadiance();
    sum.resize(pixels.size(), 0.0);
    for (std::size_t i = 0; i < pixels.size(); ++i) sum[i] += pixels[i];
    if (onSample) onSample(k);
  }
  std::vector<float> mean(sum.size());
  for (std::size_t i = 0; i < sum.size(); ++i) mean[i] = static_cast<float>(sum[i] / spp);
  return fromRgbaFloat(frame.width, frame.height, mean.data(), true);
}

std::vector<float> Renderer::readRadiance() const {
  std::vector<float> pixels(static_cast<std::size_t>(gpu_->width) * gpu_->height * 4);
  glGetTextureImage(gpu_->radiance, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pixels.size() * sizeof(float)),
                    pixels.data());
  return pixels;
}

std::vector<float> Renderer::readDepth() const {
  if (gpu_->samples > 1) throw Error("the depth of a multisampled frame is not read back");
  std::vector<float> depths(static_cast<std::size_t>(gpu_->width) * gpu_->height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, gpu_->framebuffer);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadPixels(0, 0, gpu_->width, gpu_->height, GL_DEPTH_COMPONENT, GL_FLOAT, depths.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return depths;
}

}  // namespace glint::gl
