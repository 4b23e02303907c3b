#include "scene/builtin_scenes.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "glint/error.h"
#include "glint/image_io.h"
#include "glint/kernel/random.h"
#include "scene/environment_map.h"
#include "scene/geometry.h"
#include "scene/gltf_loader.h"

namespace glint::scene {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

// ---- Deterministic noise ----------------------------------------------------------------------
// The kernel's glintPcg4d is a bijection with fixed integer arithmetic: the same bytes everywhere.

float hashUnit(int x, int y, std::uint32_t seed) {
  const glm::uvec4 h = kernel::glintPcg4d(glm::uvec4(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), seed, 0u));
  return kernel::glintHashToUnitOpen(h.x);
}

// Value noise in [0, 1): smoothstep interpolation of lattice hashes.
float valueNoise(glm::vec2 p, std::uint32_t seed) {
  const glm::vec2 cell = glm::floor(p);
  const glm::vec2 f = p - cell;
  const glm::vec2 w = f * f * (3.0f - 2.0f * f);
  const int x = static_cast<int>(cell.x);
  const int y = static_cast<int>(cell.y);
  const float a = hashUnit(x, y, seed);
  const float b = hashUnit(x + 1, y, seed);
  const float c = hashUnit(x, y + 1, seed);
  const float d = hashUnit(x + 1, y + 1, seed);
  return glm::mix(glm::mix(a, b, w.x), glm::mix(c, d, w.x), w.y);
}

// Gradient noise that tiles: the lattice wraps every `period` cells in x and y, so the noise on
// [0, period.x) x [0, period.y) continues seamlessly across its edges. About [-0.7, 0.7], zero at
// the lattice points, smooth (C2, Perlin's quintic fade). In double, for the normal map's
// central differences.
double periodicGradientNoise(glm::dvec2 p, glm::ivec2 period, std::uint32_t seed) {
  const glm::dvec2 cell = glm::floor(p);
  const glm::dvec2 f = p - cell;
  const glm::dvec2 fade = f * f * f * (f * (f * 6.0 - 15.0) + 10.0);
  auto corner = [&](int i, int j) {
    const int x = ((static_cast<int>(cell.x) + i) % period.x + period.x) % period.x;
    const int y = ((static_cast<int>(cell.y) + j) % period.y + period.y) % period.y;
    const double angle = 2.0 * std::numbers::pi * hashUnit(x, y, seed);
    return std::cos(angle) * (f.x - i) + std::sin(angle) * (f.y - j);
  };
  return glm::mix(glm::mix(corner(0, 0), corner(1, 0), fade.x), glm::mix(corner(0, 1), corner(1, 1), fade.x), fade.y);
}

// ---- Arctic snow ------------------------------------------------------------------------------

constexpr int kSnowNormalMapSize = 256;    // texels on a side
constexpr double kSnowTileMetres = 1.6;     // one normal-map tile: 40 tiles across the 64 m field

// One octave of the snow's height field: `cells` lattice cells across the tile in x and y
// (unequal for drifts stretched along x), `amplitude` in metres.
struct SnowOctave {
  glm::ivec2 cells;
  double amplitude;
};

// Gentle drifts, stretched along x as if by the wind, down to bumps 2.5 cm across. The slope of
// an octave goes with amplitude x cells: the bumps are the steepest (about ten times the drifts),
// so near the camera they scatter the sun's glints into separate sparkles, while far away, where
// a pixel averages them out, the band narrows. The normals lean 7.6 degrees on average.
constexpr SnowOctave kSnowOctaves[] = {
    {{2, 3}, 0.01}, {{4, 6}, 0.006}, {{8, 8}, 0.004}, {{16, 16}, 0.004}, {{32, 32}, 0.005}, {{64, 64}, 0.004},
};

// The snow's tangent-space normal map (glTF convention: rgb = normal * 0.5 + 0.5, +x along +u, +y
// up the image, i.e. towards decreasing v; linear 8-bit), from a periodic height field by central
// differences that wrap around, so the map tiles.
Texture snowNormalMap() {
  constexpr int size = kSnowNormalMapSize;
  std::vector<double> height(static_cast<std::size_t>(size) * size);
  for (int row = 0; row < size; ++row) {
    for (int column = 0; column < size; ++column) {
      const glm::dvec2 tileUv = (glm::dvec2(column, row) + 0.5) / static_cast<double>(size);
      double h = 0.0;
      std::uint32_t seed = 21u;
      for (const SnowOctave& octave : kSnowOctaves) {
        h += octave.amplitude * periodicGradientNoise(tileUv * glm::dvec2(octave.cells), octave.cells, seed++);
      }
      height[static_cast<std::size_t>(row) * size + static_cast<std::size_t>(column)] = h;
    }
  }
  auto heightAt = [&](int column, int row) {
    return height[static_cast<std::size_t>((row + size) % size) * size + static_cast<std::size_t>((column + size) % size)];
  };
  Texture map{"snow normal", size, size, {}, false, {}};
  map.rgba.resize(static_cast<std::size_t>(size) * size * 4);
  const double texelMetres = kSnowTileMetres / size;
  for (int row = 0; row < size; ++row) {
    for (int column = 0; column < size; ++column) {
      const double slopeX = (heightAt(column + 1, row) - heightAt(column - 1, row)) / (2.0 * texelMetres);
      // +y points up the image, towards the previous row.
      const double slopeY = (heightAt(column, row - 1) - heightAt(column, row + 1)) / (2.0 * texelMetres);
      const glm::dvec3 normal = glm::normalize(glm::dvec3(-slopeX, -slopeY, 1.0));
      const std::size_t at = (static_cast<std::size_t>(row) * size + static_cast<std::size_t>(column)) * 4;
      for (int c = 0; c < 3; ++c) {
        map.rgba[at + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(std::lround((normal[c] * 0.5 + 0.5) * 255.0));
      }
      map.rgba[at + 3] = 255;
    }
  }
  return map;
}

// ---- Parquet ----------------------------------------------------------------------------------

constexpr float kPlankWidth = 0.16f;   // metres
constexpr float kPlankLength = 1.2f;   // metres
constexpr float kGapWidth = 0.004f;    // metres: about a texel at 128 texels per metre
constexpr int kTexelsPerMetre = 128;

// Where a floor point (metres, x along the planks) falls: rows of planks, each row shifted by a
// random offset, so the joints are staggered.
struct PlankPoint {
  std::uint32_t id;      // one hash per plank
  glm::vec2 local;       // metres from the plank's corner
  float edgeDistance;    // metres to the nearest plank edge
};

PlankPoint plankAt(glm::vec2 metres) {
  const int row = static_cast<int>(std::floor(metres.y / kPlankWidth));
  const float along = metres.x + kPlankLength * hashUnit(row, 0, 11u);
  const int column = static_cast<int>(std::floor(along / kPlankLength));
  PlankPoint point;
  point.id = kernel::glintPcg4d(glm::uvec4(static_cast<std::uint32_t>(row), static_cast<std::uint32_t>(column), 12u, 0u)).x;
  point.local = glm::vec2(along - column * kPlankLength, metres.y - row * kPlankWidth);
  point.edgeDistance = std::min(std::min(point.local.x, kPlankLength - point.local.x),
                                std::min(point.local.y, kPlankWidth - point.local.y));
  return point;
}

// Grain in [0, 1]: streaks along the plank, wavy across it, a different figure on every plank.
float grainAt(const PlankPoint& plank) {
  const auto seed = plank.id & 0xffffu;
  const float warp = 2.5f * valueNoise(plank.local * glm::vec2(1.5f, 20.0f), seed) +
                     0.8f * valueNoise(plank.local * glm::vec2(6.0f, 60.0f), seed + 1u);
  const float rings = 0.5f + 0.5f * std::sin(2.0f * kPi * (plank.local.y * 45.0f + warp));
  return rings * rings * rings;
}

// The floor's two textures, for a square floor of `metres` on a side. Colour: sRGB wood, a tone
// per plank, darker grain streaks and joints. Roughness (linear): R = G = the varnish's wear per
// plank (0.35 to 0.9), rougher along the grain and in the joints; B = 0 (not metallic). R scales
// the glint alpha, G the base roughness (glTF's metallicRoughness channels).
std::pair<Texture, Texture> parquetTextures(float metres) {
  const int size = static_cast<int>(metres * kTexelsPerMetre);
  Texture colour{"parquet colour", size, size, {}, true, {}};
  Texture roughness{"parquet roughness", size, size, {}, false, {}};
  colour.rgba.resize(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * 4);
  roughness.rgba.resize(colour.rgba.size());
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      // Texel centre in metres; texture rows go with v, which the floor quad lays along +z.
      const glm::vec2 metresAt = (glm::vec2(static_cast<float>(x), static_cast<float>(y)) + 0.5f) * (metres / size);
      const PlankPoint plank = plankAt(metresAt);
      const float tone = kernel::glintHashToUnitOpen(plank.id);
      const float wear = kernel::glintHashToUnitOpen(kernel::glintPcg4d(glm::uvec4(plank.id, 13u, 0u, 0u)).x);
      const float grain = grainAt(plank);
      const bool joint = plank.edgeDistance < 0.5f * kGapWidth;
      const float fine = valueNoise(metresAt * 300.0f, 14u);

      glm::vec3 wood = glm::mix(glm::vec3(0.28f, 0.14f, 0.06f), glm::vec3(0.56f, 0.33f, 0.15f), tone);
      wood *= (0.72f + 0.28f * (1.0f - grain)) * (0.94f + 0.06f * fine);
      if (joint) wood *= 0.25f;
      float rough = (0.35f + 0.55f * wear) * (0.85f + 0.3f * grain);
      if (joint) rough = 1.0f;

      const std::size_t at = (static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x)) * 4;
      for (int c = 0; c < 3; ++c) colour.rgba[at + static_cast<std::size_t>(c)] = linearToSrgb8(wood[c]);
      colour.rgba[at + 3] = 255;
      const auto r = static_cast<std::uint8_t>(std::lround(std::clamp(rough, 0.0f, 1.0f) * 255.0f));
      roughness.rgba[at + 0] = r;
      roughness.rgba[at + 1] = r;
      roughness.rgba[at + 2] = 0;
      roughness.rgba[at + 3] = 255;
    }
  }
  return {std::move(colour), std::move(roughness)};
}

// ---- Materials --------------------------------------------------------------------------------
// Glint densities are chosen from the P-NDF's spread at the footprints of a 256 x 256 render
// (docs/scenes.md, "Built-in scenes"): a coefficient of variation near 1 reads as clear glints.

GlintLayer glintLayer(float alpha, float logDensity, float uvScale) {
  GlintLayer layer;
  layer.enabled = true;
  layer.alpha = glm::vec2(alpha);
  layer.logDensity = logDensity;
  layer.uvScale = uvScale;
  return layer;
}

// Roughness consistent with a glint alpha: alpha = roughness^2 (alphaFromRoughness's inverse).
float roughnessFor(float alpha) { return std::sqrt(alpha); }

Material redGlint() {
  Material m;
  m.name = "red glint";
  m.baseColour = glm::vec4(0.6f, 0.05f, 0.05f, 1.0f);
  m.metallic = 0.0f;
  m.roughness = roughnessFor(0.5f);
  m.glint = glintLayer(0.5f, 13.0f, 4.0f);
  return m;
}

// Uses textures `colourTexture` and `roughnessTexture` from parquetTextures.
Material parquet(int colourTexture, int roughnessTexture) {
  Material m;
  m.name = "parquet";
  m.baseColourTexture = colourTexture;
  m.metallic = 0.0f;
  m.roughness = 0.6f;
  m.metallicRoughnessTexture = roughnessTexture;
  m.glint = glintLayer(0.35f, 12.0f, 4.0f);
  m.glint.roughnessTexture = roughnessTexture;
  return m;
}

Material carPaint() {
  Material m;
  m.name = "car paint";
  m.baseColour = glm::vec4(0.02f, 0.05f, 0.35f, 1.0f);
  m.metallic = 1.0f;
  m.roughness = roughnessFor(0.3f);
  m.glint = glintLayer(0.3f, 12.0f, 4.0f);
  m.glint.colouredCells = true;
  // The clear coat over the flakes (KHR_materials_clearcoat): smooth, as a car's lacquer.
  m.clearcoat.factor = 1.0f;
  m.clearcoat.roughness = 0.1f;
  return m;
}

Material matte(const char* name, glm::vec3 colour) {
  Material m;
  m.name = name;
  m.baseColour = glm::vec4(colour, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 0.8f;
  return m;
}

Material plainGrey(const char* name, float albedo) { return matte(name, glm::vec3(albedo)); }

Material sparklingStone() {
  Material m;
  m.name = "sparkling stone";
  m.baseColour = glm::vec4(0.12f, 0.12f, 0.13f, 1.0f);  // dark granite, against which sparkles stand out
  m.metallic = 0.0f;
  m.roughness = roughnessFor(0.2f);
  m.glint = glintLayer(0.2f, 11.0f, 6.0f);
  return m;
}

Material glitterCurtain() {
  Material m;
  m.name = "glitter curtain";
  m.baseColour = glm::vec4(0.16f, 0.02f, 0.24f, 1.0f);
  m.metallic = 0.0f;
  m.roughness = roughnessFor(0.4f);
  m.glint = glintLayer(0.4f, 14.0f, 4.0f);
  m.glint.relativeArea = 0.3f;  // only some cells hold flakes: scattered sparkles on cloth
  m.doubleSided = true;         // a single sheet, seen from either side
  return m;
}

// Snow: a white diffuse base with the sparse, sharp glints of the arctic scene of Chermain et al.
// 2021 (alpha 0.05, log density 10.52, relative area 0.25: three cells in four hold no flakes).
// `glintUvScale` is the mesh's uv per glint uv; kSnowGlintUvPerMetre keeps the sparkles the same
// size on every snow surface.
constexpr float kSnowGlintUvPerMetre = 6.25f;  // the paper's uv scale of 10 per 1.6 m tile

Material snow(const char* name, float alpha, float glintUvScale) {
  Material m;
  m.name = name;
  m.baseColour = glm::vec4(0.86f, 0.89f, 0.93f, 1.0f);  // slightly blue: fresh snow's albedo
  m.metallic = 0.0f;
  m.roughness = roughnessFor(alpha);
  m.glint = glintLayer(alpha, 10.52f, glintUvScale);
  m.glint.relativeArea = 0.25f;
  return m;
}

Material sparklySilver() {
  Material m;
  m.name = "sparkly silver";
  m.baseColour = glm::vec4(0.92f, 0.92f, 0.95f, 1.0f);
  m.metallic = 1.0f;
  m.roughness = roughnessFor(0.3f);
  m.glint = glintLayer(0.3f, 12.0f, 40.0f);  // uv in metres (makeTorus)
  return m;
}

// The atrium's floor: pale sandstone whose sparse mineral grains glitter (one cell in twenty holds
// microfacets), visible near the camera.
Material sandstoneFloor() {
  Material m;
  m.name = "sandstone floor";
  m.baseColour = glm::vec4(0.22f, 0.2f, 0.16f, 1.0f);
  m.metallic = 0.0f;
  m.roughness = roughnessFor(0.15f);
  m.glint = glintLayer(0.15f, 9.0f, 6.0f);  // uv in metres
  m.glint.relativeArea = 0.05f;
  return m;
}

// The atrium's glitter curtains: dyed cloth whose every cell holds flakes (relative area 1, twenty
// times the floor's).
Material glitterCloth(const char* name, glm::vec3 colour) {
  Material m;
  m.name = name;
  m.baseColour = glm::vec4(colour, 1.0f);
  m.metallic = 0.0f;
  m.roughness = roughnessFor(0.4f);
  m.glint = glintLayer(0.4f, 10.0f, 4.0f);  // uv in metres
  m.doubleSided = true;
  return m;
}

int addMaterial(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return static_cast<int>(scene.materials.size()) - 1;
}

int addTexture(Scene& scene, Texture texture) {
  scene.textures.push_back(std::move(texture));
  return static_cast<int>(scene.textures.size()) - 1;
}

// ---- Shapes -----------------------------------------------------------------------------------

// A superellipse (|x/a|^p + |r/b|^p = 1) as a lathe profile, by angle so that the tips get as many
// rings as the flanks; exact zeros at the ends close the body.
std::function<ProfilePoint(float)> superellipse(float a, float b, float p) {
  return [=](float t) {
    const float angle = kPi * t;
    const float c = t <= 0.0f ? 1.0f : (t >= 1.0f ? -1.0f : std::cos(angle));
    const float s = (t <= 0.0f || t >= 1.0f) ? 0.0f : std::sin(angle);
    const float cx = std::pow(std::abs(c), 2.0f / p);
    const float sr = std::pow(s, 2.0f / p);
    // The gradient of the implicit form, |x/a|^(p-1) / a and |r/b|^(p-1) / b.
    const glm::vec2 normal(std::copysign(std::pow(cx, p - 1.0f) / a, c), std::pow(sr, p - 1.0f) / b);
    return ProfilePoint{std::copysign(a * cx, c), b * sr, normal};
  };
}

// A car-like body of revolution around x, `scale` = 1 for about 4 m long, with a cabin on top.
void addCar(Scene& scene, int material, glm::vec3 groundCentre, float scale) {
  const float bodyRadius = 0.55f * scale;
  const glm::vec3 bodyCentre = groundCentre + glm::vec3(0.0f, 0.2f * scale + bodyRadius, 0.0f);
  scene.meshes.push_back(makeLathe("car body", material, bodyCentre, 64, 160, superellipse(2.0f * scale, bodyRadius, 2.6f)));
  const glm::vec3 cabinCentre = bodyCentre + glm::vec3(-0.25f * scale, 0.42f * scale, 0.0f);
  scene.meshes.push_back(makeLathe("car cabin", material, cabinCentre, 48, 64, superellipse(1.05f * scale, 0.42f * scale, 2.2f)));
}

// A curtain: a sheet `width` x `height` metres hanging with its bottom at y0, its middle line
// through `origin` (whose y is 0), running along the horizontal unit vector `along` and folded as a
// sine of amplitude `depth` towards `facing` (horizontal, unit, perpendicular to `along`); `grid`
// cells along and down. uv in metres, v growing downwards (unmirrored seen from `facing`).
Mesh curtain(int material, glm::vec3 origin, glm::vec3 along, glm::vec3 facing, float width, float height, float y0,
             float depth, float foldWidth, glm::ivec2 grid) {
  const float k = 2.0f * kPi / foldWidth;
  return makeParametricSurface("curtain", material, grid.x, grid.y, [=](float s, float t) {
    const float x = (s - 0.5f) * width;
    const float y = y0 + (1.0f - t) * height;
    const float fold = depth * std::sin(k * x);
    const float slope = depth * k * std::cos(k * x);  // d fold / dx
    return SurfacePoint{origin + x * along + fold * facing + glm::vec3(0.0f, y, 0.0f), -slope * along + facing,
                        glm::vec2(s * width, t * height)};
  });
}

// ---- Atrium ------------------------------------------------------------------------------------

// A body of revolution about the unit vector `axis` through `base`, its profile a Catmull-Rom curve
// through (radius, height along the axis) points (metres), `segments` around and `rings` along;
// rings are spread over the control polygon's length, so that mouldings get as many as a plain
// shaft. The normals point away from the axis where the profile climbs along it, towards +axis
// where it comes in towards the axis. Open at both ends (a point on the axis closes it); uv: (angle
// / 2 pi, height in metres).
Mesh makeTurnedProfile(std::string name, int material, glm::vec3 base, glm::vec3 axis, const std::vector<glm::vec2>& points,
                       int segments, int rings) {
  const glm::vec3 first = anyPerpendicular(axis);
  const glm::vec3 second = glm::cross(axis, first);
  const int last = static_cast<int>(points.size()) - 1;
  std::vector<float> start(points.size(), 0.0f);  // arc length of the control polygon up to each point
  for (int i = 1; i <= last; ++i) start[i] = start[i - 1] + glm::length(points[i] - points[i - 1]);
  auto point = [&](int i) { return points[static_cast<std::size_t>(std::clamp(i, 0, last))]; };
  return makeParametricSurface(std::move(name), material, segments, rings, [=](float s, float t) {
    // The segment and the local parameter tau at arc length t * total.
    const float at = t * start[last];
    int i = 0;
    while (i < last - 1 && at > start[i + 1]) ++i;
    const float tau = t >= 1.0f ? 1.0f : std::clamp((at - start[i]) / (start[i + 1] - start[i]), 0.0f, 1.0f);
    const glm::vec2 p0 = point(i - 1), p1 = point(i), p2 = point(i + 1), p3 = point(i + 2);
    const glm::vec2 a = -p0 + p2, b = 2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3, c = -p0 + 3.0f * p1 - 3.0f * p2 + p3;
    const glm::vec2 profile = p1 + 0.5f * tau * (a + tau * (b + tau * c));
    const glm::vec2 slope = 0.5f * (a + tau * (2.0f * b + 3.0f * tau * c));  // d profile / d tau: (dr, dy)
    const float angle = s >= 1.0f ? 0.0f : 2.0f * kPi * s;
    const glm::vec3 radial = std::cos(angle) * first + std::sin(angle) * second;
    // Perpendicular to the profile's tangent (dr, dh) in the (radial, axis) plane.
    const glm::vec3 normal = slope.y * radial - slope.x * axis;
    return SurfacePoint{base + profile.x * radial + profile.y * axis, normal, glm::vec2(s, profile.y)};
  });
}

// A column `height` metres tall standing at `ground`, shaft radius `radius` at its foot: a square
// plinth, a torus moulding, a tapering shaft with a ring at its neck, a flaring capital and a
// square abacus on which arches rest (its top at `height`).
void addColumn(Scene& scene, int material, glm::vec3 ground, float height, float radius, int segments, int rings) {
  const float r = radius;
  const float plinth = 0.25f * r / 0.3f;     // proportions of a 0.3 m column
  const float abacus = 0.2f * r / 0.3f;
  const float top = height - abacus;
  const std::vector<glm::vec2> profile = {
      {1.25f * r, plinth},          {1.3f * r, plinth + 0.05f * r},  {1.18f * r, plinth + 0.22f * r},
      {1.02f * r, plinth + 0.33f * r}, {r, plinth + 0.5f * r},         {0.93f * r, 0.55f * top},
      {0.86f * r, top - 0.75f * r}, {0.98f * r, top - 0.68f * r},  {0.86f * r, top - 0.6f * r},
      {0.95f * r, top - 0.4f * r},  {1.35f * r, top - 0.08f * r},  {1.45f * r, top}};
  scene.meshes.push_back(makeTurnedProfile("column", material, ground, glm::vec3(0, 1, 0), profile, segments, rings));
  scene.meshes.push_back(makeBox("column plinth", material, ground + glm::vec3(0.0f, 0.5f * plinth, 0.0f),
                                 glm::vec3(1.4f * r, 0.5f * plinth, 1.4f * r), 1.0f));
  scene.meshes.push_back(makeBox("column abacus", material, ground + glm::vec3(0.0f, top + 0.5f * abacus, 0.0f),
                                 glm::vec3(1.55f * r, 0.5f * abacus, 1.55f * r), 1.0f));
}

// The face of a wall over a round arch: the plane through `origin` (its foot at the bay's start)
// spanning `span` metres along the horizontal unit vector `along`, from the springing height up to
// `top`, less the half disc of radius `archRadius` centred mid-span on the springing line; its
// normal is `facing`. Vertical rulings from the arch (and the flat beds beside it) up to the top,
// `columns` along the bottom edge by arc length, `rows` up. uv in metres.
Mesh archedWallFace(int material, glm::vec3 origin, glm::vec3 along, glm::vec3 facing, float span, float archRadius,
                    float springing, float top, int columns, int rows) {
  const float bed = 0.5f * span - archRadius;  // the flat beds on either side of the arch
  const float length = 2.0f * bed + kPi * archRadius;
  return makeParametricSurface("arcade wall", material, columns, rows, [=](float s, float t) {
    const float at = s * length;
    glm::vec2 bottom;  // (along, up) of the bottom edge
    if (at <= bed) {
      bottom = {at, springing};
    } else if (at >= bed + kPi * archRadius) {
      bottom = {s >= 1.0f ? span : at - kPi * archRadius + 2.0f * archRadius, springing};
    } else {
      const float angle = (at - bed) / archRadius;  // 0 at the arch's start, pi at its end
      bottom = {0.5f * span - archRadius * std::cos(angle), springing + archRadius * std::sin(angle)};
    }
    const float up = t >= 1.0f ? top : glm::mix(bottom.y, top, t);
    return SurfacePoint{origin + bottom.x * along + glm::vec3(0.0f, up, 0.0f), facing, glm::vec2(bottom.x, up)};
  });
}

// The underside of a round arch through a wall: the half cylinder of radius `archRadius` about the
// springing line mid-span, from `origin` (the wall's foot at the bay's start, on one face) across
// `thickness` metres along `across`; its normals point to the arch's axis. uv in metres.
Mesh archIntrados(int material, glm::vec3 origin, glm::vec3 along, glm::vec3 across, float span, float archRadius,
                  float springing, float thickness, int segments) {
  return makeParametricSurface("arch intrados", material, segments, 1, [=](float s, float t) {
    const float angle = s >= 1.0f ? kPi : kPi * s;
    const float alongArch = 0.5f * span - archRadius * std::cos(angle);
    const glm::vec3 position = origin + alongArch * along + t * thickness * across +
                               glm::vec3(0.0f, springing + archRadius * std::sin(angle), 0.0f);
    const glm::vec3 normal = std::cos(angle) * along - std::sin(angle) * glm::vec3(0, 1, 0);
    return SurfacePoint{position, normal, glm::vec2(archRadius * angle, t * thickness)};
  });
}

// ---- Car ---------------------------------------------------------------------------------------

// sign(x) |x|^p: a superellipse's coordinate.
template <typename Real>
Real signedPower(Real x, Real p) {
  return std::copysign(std::pow(std::abs(x), p), x);
}

// The car's body, front towards +x, wheels on the ground at y = 0: a loft of rounded-rectangle
// (superellipse) sections along x whose top follows a side profile (bonnet, windscreen, roof,
// sloping tail) and whose upper part leans in (tumblehome), its ends rounded off by a superellipse
// along x. Dimensions in metres, about a Citroen 2CV's.
struct CarBody {
  float halfLength = 1.95f;
  float halfWidth = 0.76f;
  float bottom = 0.36f;   // the sill, above the wheels' centres
  float belt = 1.0f;      // the windows' sills
  float roof = 1.6f;

  // The top of the section at x: the bonnet rising to the scuttle, the windscreen, the roof and
  // the tail sloping down to the rear. (In double for the paint's uv, CarPaintUv.)
  template <typename Real>
  Real top(Real x) const {
    const Real bonnet = Real(0.84) + Real(0.16) * glm::smoothstep(Real(1.95), Real(0.75), x);
    const Real cabin = glm::smoothstep(Real(0.8), Real(0.22), x);
    const Real tail = Real(roof) - Real(0.68) * std::pow(glm::smoothstep(Real(-0.65), Real(-1.95), x), Real(1.3));
    return glm::mix(bonnet, tail, cabin);
  }
  // The half width at x and height y: narrower at the nose, leaning in above the belt.
  template <typename Real>
  Real width(Real x, Real y) const {
    const Real nose = Real(1) - Real(0.12) * glm::smoothstep(Real(0.9), Real(1.95), x);
    return Real(halfWidth) * nose * (Real(1) - Real(0.27) * glm::smoothstep(Real(belt) - Real(0.05), Real(roof), y));
  }
  // The section at s along the body (0 rear, 1 front): where it lies on x, and its size, 1 in the
  // middle falling to 0 at both ends (a superellipse along x). In double, as what is built on it:
  // WebAssembly's float sin and pow differ from glibc's in the last bit, their double ones far
  // below a float's, and the page must draw the desktop's image.
  struct Station {
    double x;
    double size;
  };
  Station station(float s) const {
    const double along = std::numbers::pi * (static_cast<double>(s) - 0.5);
    return {halfLength * signedPower(std::sin(along), 0.45), s <= 0.0f || s >= 1.0f ? 0.0 : std::pow(std::cos(along), 0.45)};
  }
  // The point at s along the body and t around its section (0 and 1 under the middle of the
  // floor), rounded to float.
  glm::vec3 position(float s, float t) const {
    const Station at = station(s);
    const double around = 2.0 * std::numbers::pi * static_cast<double>(t);
    const double height = top(at.x) - bottom;
    const double y = bottom + 0.5 * height * (1.0 - at.size * signedPower(std::cos(around), 0.4));
    return glm::vec3(glm::dvec3(at.x, y, width(at.x, y) * at.size * signedPower(std::sin(around), 0.4)));
  }
  // The section's centre line, which the normals point away from.
  glm::vec3 axis(float s) const {
    const double x = station(s).x;
    return glm::vec3(glm::dvec3(x, 0.5 * (bottom + top(x)), 0.0));
  }
};

// The car body's paint uv, about a metre of surface a unit both ways, so that the flakes are as
// dense on the nose and the tail as on the doors (a uv linear in the loft's (s, t) crowded them
// there up to 20 times: the sections shrink to a point at both ends and x changes slowly there).
// Along the body: x, plus about the distance the meridian travels round the rounded end,
// (1 - size) r. Around: the arc length of the middle section's superellipse up to t, as a fraction
// of its perimeter (tabulated once, below), times the section's perimeter, estimated as
// 2 (height + 2 half width) times its size. In double, rounded to float, as the positions
// (CarBody::station).
class CarPaintUv {
 public:
  explicit CarPaintUv(const CarBody& body) : body_(body), aroundFraction_(kTableSize + 1) {
    const double height = body.top(0.0) - body.bottom;
    const double halfWidth = body.width(0.0, body.bottom + 0.5 * height);
    double length = 0.0;
    glm::dvec2 previous = sectionPoint(0.0, height, halfWidth);
    for (int i = 1; i <= kTableSize; ++i) {
      const glm::dvec2 point = sectionPoint(static_cast<double>(i) / kTableSize, height, halfWidth);
      length += glm::length(point - previous);
      aroundFraction_[static_cast<std::size_t>(i)] = length;
      previous = point;
    }
    for (double& f : aroundFraction_) f = f / length - 0.5;  // -0.5 under the floor, 0 on the roof
  }

  glm::vec2 operator()(float s, float t) const {
    // The ends' rounding, metres: with 0.3 the nose and the tail hold the doors' flake density
    // within 10% (BuiltinScenes.CarPaintFlakesAreAsDenseOnTheNoseAsOnTheDoors).
    constexpr double kEndRadius = 0.3;
    // About the doors' median flake density under the loft's former uv, which varied along them.
    constexpr double kUvPerMetre = 0.93;
    const CarBody::Station at = body_.station(s);
    const double alongEnd = (s < 0.5f ? -1.0 : s > 0.5f ? 1.0 : 0.0) * (1.0 - at.size) * kEndRadius;
    const double height = body_.top(at.x) - body_.bottom;
    const double perimeter = at.size * 2.0 * (height + 2.0 * body_.width(at.x, body_.bottom + 0.5 * height));
    return glm::vec2(kUvPerMetre * glm::dvec2(at.x + alongEnd, around(t) * perimeter));
  }

 private:
  static constexpr int kTableSize = 4096;
  // The middle section's outline at t (CarBody::position's superellipse), in its plane.
  static glm::dvec2 sectionPoint(double t, double height, double halfWidth) {
    const double around = 2.0 * std::numbers::pi * t;
    return {0.5 * height * signedPower(std::cos(around), 0.4), halfWidth * signedPower(std::sin(around), 0.4)};
  }
  double around(float t) const {
    const double at = std::clamp(static_cast<double>(t), 0.0, 1.0) * kTableSize;
    const int i = std::min(static_cast<int>(at), kTableSize - 1);
    const double f = at - i;
    return aroundFraction_[static_cast<std::size_t>(i)] * (1.0 - f) + aroundFraction_[static_cast<std::size_t>(i) + 1] * f;
  }
  const CarBody& body_;
  std::vector<double> aroundFraction_;
};

// Where the body is glass, for a triangle at `p` with normal `n`: the windscreen, a side window
// each side of the B pillar, the rear window.
bool carWindow(const CarBody& body, glm::vec3 p, glm::vec3 n) {
  if (p.y < body.belt + 0.05f) return false;
  const float edge = body.width(p.x, p.y);
  const bool windscreen = p.x > 0.2f && p.x < 0.78f && n.x > 0.35f && std::abs(p.z) < 0.8f * edge;
  const bool side = std::abs(n.z) > 0.55f && p.y < body.top(p.x) - 0.1f && p.x > -1.05f && p.x < 0.42f &&
                    std::abs(p.x + 0.3f) > 0.06f;
  const bool rear = p.x < -1.0f && n.x < -0.35f && std::abs(p.z) < 0.72f * edge && p.y > body.belt + 0.1f;
  return windscreen || side || rear;
}

// A wheel at `hub` (on the axle, at the tyre's outer face), `outwards` the unit axle direction
// away from the car: a tyre with a rounded-square section and a dished rim with a hub cap.
void addWheel(Scene& scene, int rubber, int rim, glm::vec3 hub, glm::vec3 outwards, float radius) {
  const float tyreHalfWidth = 0.09f;
  const float tyreHalfHeight = 0.075f;
  const glm::vec3 centre = hub - tyreHalfWidth * outwards;
  const glm::vec3 first = anyPerpendicular(outwards);
  const glm::vec3 second = glm::cross(outwards, first);
  const float ring = radius - tyreHalfHeight;  // the tread's middle is `radius` from the axle
  auto tyre = [=](float s, float t) {
    const float a = s >= 1.0f ? 0.0f : 2.0f * kPi * s;
    const float b = 2.0f * kPi * t;
    const glm::vec3 radial = std::cos(a) * first + std::sin(a) * second;
    return centre + (ring + tyreHalfHeight * signedPower(std::cos(b), 0.5f)) * radial +
           tyreHalfWidth * signedPower(std::sin(b), 0.5f) * outwards;
  };
  auto tubeCentre = [=](float s, float) {
    const float a = 2.0f * kPi * s;
    return centre + ring * (std::cos(a) * first + std::sin(a) * second);
  };
  scene.meshes.push_back(makeSurfaceFromPositions(
      "tyre", rubber, 72, 28, true, tyre, tubeCentre, [=](float, float) { return outwards; },
      [=](float s, float t) { return glm::vec2(s * 2.0f * kPi * radius, t); }));
  // The rim, from where it meets the tyre in to the hub cap's dome, its face turned outwards.
  const float inner = ring - tyreHalfHeight;
  const std::vector<glm::vec2> profile = {{inner + 0.01f, -0.03f}, {inner - 0.01f, 0.0f}, {0.7f * inner, -0.02f},
                                          {0.45f * inner, 0.0f},    {0.4f * inner, 0.04f},  {0.2f * inner, 0.07f},
                                          {0.0f, 0.075f}};
  scene.meshes.push_back(makeTurnedProfile("rim", rim, centre + 0.05f * outwards, outwards, profile, 64, 24));
}

// The point of a sphere at `elevation` above its equator and `azimuth` to the left of `facing`
// (a horizontal unit vector), radians.
glm::vec3 onSphere(glm::vec3 centre, float radius, glm::vec3 facing, float azimuth, float elevation) {
  const glm::vec3 left = glm::cross(glm::vec3(0, 1, 0), facing);
  const glm::vec3 horizontal = std::cos(azimuth) * facing + std::sin(azimuth) * left;
  return centre + radius * (std::cos(elevation) * horizontal + std::sin(elevation) * glm::vec3(0, 1, 0));
}

// A snowman standing at `ground`, 2.2 m tall, its face towards `facing` (horizontal, unit): three
// snow balls settled into each other, coal eyes and buttons, a carrot nose. Ball uvs in metres.
void addSnowman(Scene& scene, int snowMaterial, int coal, int carrot, glm::vec3 ground, glm::vec3 facing) {
  struct Ball {
    const char* name;
    float radius;
    float sink;  // how far it settles into what is below
  };
  constexpr Ball kBalls[] = {{"snowman base", 0.55f, 0.08f}, {"snowman body", 0.4f, 0.1f}, {"snowman head", 0.27f, 0.06f}};
  glm::vec3 centres[3];
  float top = ground.y;
  for (int i = 0; i < 3; ++i) {
    const Ball& ball = kBalls[i];
    centres[i] = glm::vec3(ground.x, top - ball.sink + ball.radius, ground.z);
    top = centres[i].y + ball.radius;
    const glm::vec2 metres = ball.radius * glm::vec2(2.0f * kPi, kPi);
    scene.meshes.push_back(makeUvSphere(ball.name, snowMaterial, centres[i], ball.radius, 64, 32, metres));
  }
  const float head = kBalls[2].radius;
  for (float side : {-1.0f, 1.0f}) {
    scene.meshes.push_back(makeUvSphere("snowman eye", coal, onSphere(centres[2], head, facing, side * 0.35f, 0.3f), 0.03f, 12, 6));
  }
  for (float elevation : {-0.1f, 0.3f, 0.7f}) {
    scene.meshes.push_back(makeUvSphere("snowman button", coal, onSphere(centres[1], kBalls[1].radius, facing, 0.0f, elevation),
                                        0.035f, 12, 6));
  }
  const glm::vec3 noseBase = onSphere(centres[2], 0.8f * head, facing, 0.0f, 0.05f);
  // Its open base lies inside the head.
  scene.meshes.push_back(makeCone("snowman nose", carrot, noseBase, facing, 0.045f, 0.28f, 24));
}

// A snowflake ornament of silver tube rings, resting on one of its petals: a central ring and six
// petal rings around it touching it, in a plane that faces `facing` (horizontal, unit) and leans
// back by `lean` radians, turning the rings' tops towards the sky and the lights. Every other
// petal tilts out of the plane, so the rings catch the light at different angles. Returns the
// centre of the central ring.
glm::vec3 addSnowflakeOrnament(Scene& scene, int material, glm::vec3 ground, glm::vec3 facing, float lean) {
  constexpr float kCentreRadius = 0.3f;
  constexpr float kPetalRadius = 0.18f;
  constexpr float kTube = 0.03f;
  constexpr float kPetalDistance = kCentreRadius + kPetalRadius;  // petals touch the centre ring
  constexpr float kTilt = 0.45f;                                    // radians, every other petal
  constexpr float kSink = 0.01f;                                    // into the snow
  constexpr float kUvPerMetre = 1.0f;                               // the material's uv_scale sets the density
  const glm::vec3 up(0, 1, 0);
  const glm::vec3 across = glm::cross(up, facing);
  const glm::vec3 flakeUp = std::cos(lean) * up - std::sin(lean) * facing;
  const glm::vec3 flakeAxis = std::cos(lean) * facing + std::sin(lean) * up;
  // The lowest point is the bottom petal's (untilted, in the flake's plane).
  const float height = (kPetalDistance + kPetalRadius) * std::cos(lean) + kTube - kSink;
  const glm::vec3 centre = ground + height * up;
  scene.meshes.push_back(makeTorus("ornament centre", material, centre, flakeAxis, kCentreRadius, kTube, 96, 16, kUvPerMetre));
  for (int petal = 0; petal < 6; ++petal) {
    // Petal 0 points down, onto the snow.
    const float angle = -0.5f * kPi + static_cast<float>(petal) * kPi / 3.0f;
    const glm::vec3 radial = std::cos(angle) * across + std::sin(angle) * flakeUp;
    // Tilting turns the petal's axis about its radial direction.
    const float tilt = petal % 2 == 0 ? 0.0f : kTilt;
    const glm::vec3 axis = std::cos(tilt) * flakeAxis + std::sin(tilt) * glm::cross(radial, flakeAxis);
    scene.meshes.push_back(makeTorus("ornament petal", material, centre + kPetalDistance * radial, axis, kPetalRadius, kTube,
                                     64, 16, kUvPerMetre));
  }
  return centre;
}

// ---- Lighting ---------------------------------------------------------------------------------

Light pointLight(glm::vec3 position, glm::vec3 intensity) {
  Light light;
  light.type = Light::Type::Point;
  light.position = position;
  light.intensity = intensity;
  return light;
}

Light directionalLight(glm::vec3 direction, glm::vec3 irradiance) {
  Light light;
  light.type = Light::Type::Directional;
  light.direction = glm::normalize(direction);
  light.intensity = irradiance;
  return light;
}

// An equirectangular 128 x 64 sky: blue zenith fading to a pale horizon, grey ground below.
Environment sky(float intensity) {
  Environment environment;
  environment.width = 128;
  environment.height = 64;
  environment.intensity = intensity;
  environment.pixels.resize(static_cast<std::size_t>(environment.width) * static_cast<std::size_t>(environment.height));
  for (int y = 0; y < environment.height; ++y) {
    const float elevation = 0.5f * kPi - kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(environment.height);
    const glm::vec3 colour = skyRadiance(elevation);
    for (int x = 0; x < environment.width; ++x) {
      environment.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(environment.width) + static_cast<std::size_t>(x)] = colour;
    }
  }
  return environment;
}

// A unit vector `azimuthDegrees` to the left of -z (the built-in views' forward) and
// `elevationDegrees` above the horizon.
glm::vec3 horizonDirection(float azimuthDegrees, float elevationDegrees) {
  const float azimuth = glm::radians(azimuthDegrees);
  const float elevation = glm::radians(elevationDegrees);
  return {-std::sin(azimuth) * std::cos(elevation), std::sin(elevation), -std::cos(azimuth) * std::cos(elevation)};
}

Camera camera(glm::vec3 position, glm::vec3 target, float fovDegrees = 45.0f) {
  Camera c;
  c.position = position;
  c.target = target;
  c.up = glm::vec3(0, 1, 0);
  c.verticalFovDegrees = fovDegrees;
  return c;
}

// The bounding-box presets (front, side, top, close) with the scene's own default.
void setCameras(Scene& scene, const Camera& defaultCamera) {
  scene.cameras = scene.presetCameras = standardCameras(scene.boundsMin(), scene.boundsMax());
  scene.cameras["default"] = defaultCamera;
}

// ---- The scenes -------------------------------------------------------------------------------

Scene sphereScene() {
  Scene scene;
  scene.name = "sphere";
  const int red = addMaterial(scene, redGlint());
  scene.meshes.push_back(makeUvSphere("sphere", red, glm::vec3(0.0f), 1.0f, 128, 64));
  // One light, up and to the right of the camera, so the highlight and its glints sit on the
  // upper right of the sphere.
  scene.lights.push_back(pointLight({3.0f, 3.0f, 5.0f}, glm::vec3(60.0f)));
  scene.environment.uniform = glm::vec3(0.02f);
  // A unit sphere spans 70% of the frame's height when tan(asin(1 / d)) = 0.7 tan(22.5 deg): d = 3.6.
  setCameras(scene, camera({0.0f, 0.0f, 3.6f}, glm::vec3(0.0f)));
  return scene;
}

Scene parquetScene() {
  Scene scene;
  scene.name = "parquet";
  constexpr float kSize = 4.0f;
  auto [colour, roughness] = parquetTextures(kSize);
  const int colourTexture = addTexture(scene, std::move(colour));
  const int roughnessTexture = addTexture(scene, std::move(roughness));
  const int wood = addMaterial(scene, parquet(colourTexture, roughnessTexture));
  scene.meshes.push_back(makeQuad("floor", wood, glm::vec3(0.0f), {0.5f * kSize, 0, 0}, {0, 0, 0.5f * kSize}));
  // The point light sits beyond the centre, so its reflection (and the glints around it) lies in
  // the middle of the grazing view.
  scene.lights.push_back(pointLight({0.5f, 1.2f, -1.5f}, glm::vec3(5.0f)));
  scene.lights.push_back(directionalLight({-0.3f, -1.0f, -0.4f}, glm::vec3(0.8f, 0.78f, 0.75f)));
  scene.environment.uniform = glm::vec3(0.08f, 0.08f, 0.09f);
  // 25 degrees above the floor, 4.5 m from its centre.
  const float elevation = glm::radians(25.0f);
  setCameras(scene, camera(4.5f * glm::vec3(0.0f, std::sin(elevation), std::cos(elevation)), glm::vec3(0.0f)));
  // The whole floor from above: half of 4 m fits tan(22.5 deg) * 5.5 m.
  Camera top = camera({0.0f, 5.5f, 0.0f}, glm::vec3(0.0f));
  top.up = glm::vec3(0, 0, -1);
  scene.cameras["top"] = top;
  return scene;
}

Scene carpaintScene() {
  Scene scene;
  scene.name = "carpaint";
  const int paint = addMaterial(scene, carPaint());
  const int floor = addMaterial(scene, plainGrey("floor", 0.18f));
  addCar(scene, paint, glm::vec3(0.0f), 1.0f);
  scene.meshes.push_back(makeQuad("floor", floor, glm::vec3(0.0f), {6, 0, 0}, {0, 0, 6}, glm::vec2(12.0f)));
  scene.lights.push_back(pointLight({2.0f, 4.0f, 3.0f}, glm::vec3(40.0f)));
  scene.lights.push_back(directionalLight({-0.5f, -1.0f, -0.3f}, glm::vec3(1.0f, 0.97f, 0.92f)));
  scene.environment = sky(0.5f);
  setCameras(scene, camera({3.6f, 1.8f, 4.4f}, {0.0f, 0.6f, 0.0f}));
  return scene;
}

Scene showroomScene() {
  Scene scene;
  scene.name = "showroom";
  constexpr float kFloor = 8.0f;
  auto [colour, roughness] = parquetTextures(kFloor);
  const int colourTexture = addTexture(scene, std::move(colour));
  const int roughnessTexture = addTexture(scene, std::move(roughness));
  const int wood = addMaterial(scene, parquet(colourTexture, roughnessTexture));
  const int stone = addMaterial(scene, sparklingStone());
  const int red = addMaterial(scene, redGlint());
  const int paint = addMaterial(scene, carPaint());
  const int cloth = addMaterial(scene, glitterCurtain());

  scene.meshes.push_back(makeQuad("parquet floor", wood, glm::vec3(0.0f), {0.5f * kFloor, 0, 0}, {0, 0, 0.5f * kFloor}));
  // A low stone stage at the front left with the sphere on it, the car at the right, the curtain
  // along the back.
  const glm::vec3 stageCentre(-1.6f, 0.1f, 0.4f);
  const glm::vec3 stageHalf(0.7f, 0.1f, 0.7f);
  scene.meshes.push_back(makeBox("stone stage", stone, stageCentre, stageHalf, 1.0f));
  const float sphereRadius = 0.45f;
  scene.meshes.push_back(makeUvSphere("sphere", red, stageCentre + glm::vec3(0.0f, stageHalf.y + sphereRadius, 0.0f),
                                      sphereRadius, 96, 48));
  addCar(scene, paint, glm::vec3(1.5f, 0.0f, -0.6f), 0.6f);
  scene.meshes.push_back(curtain(cloth, {0.0f, 0.0f, -3.5f}, {1, 0, 0}, {0, 0, 1}, 7.0f, 3.2f, 0.02f, 0.08f, 0.45f, {160, 40}));

  // Glints show where a light's mirror image lies, so each light has a surface to sparkle on as
  // seen from the default camera: the key on the sphere, car and curtain; the back-left light
  // mirrors in the stage's top at about (-1.5, 0.2, 0.9); the right one in the floor at the lower right.
  scene.lights.push_back(pointLight({0.5f, 3.5f, 2.5f}, glm::vec3(36.0f)));                  // key
  scene.lights.push_back(pointLight({-2.6f, 1.8f, -2.4f}, glm::vec3(16.0f, 14.0f, 12.0f)));     // warm, back left
  scene.lights.push_back(pointLight({3.0f, 3.0f, -2.0f}, glm::vec3(12.0f, 13.0f, 16.0f)));   // cool, back right
  scene.environment = sky(0.15f);

  setCameras(scene, camera({0.0f, 2.4f, 5.4f}, {0.0f, 0.6f, -1.0f}));
  scene.cameras["wide"] = camera({4.5f, 3.2f, 6.0f}, {0.0f, 0.8f, -1.2f}, 60.0f);
  scene.cameras["curtain"] = camera({0.5f, 1.6f, -1.0f}, {0.0f, 1.6f, -3.5f});
  scene.cameras["car"] = camera({3.2f, 1.2f, 1.4f}, {1.5f, 0.45f, -0.6f});
  return scene;
}

// The atrium: after the Sponza atrium of Chermain et al. 2020's performance table (262,267
// triangles), glint's own geometry of the same size. A nave 10 m wide and 32 m long between two
// storeys of round-arched arcades on columns, aisles and a gallery behind them, a sandstone floor
// with sparse glittering grains, red, green and blue glitter curtains hanging between the columns of
// both storeys, a great arch at the far end; open to the sky, lit by a high sun and three lamps
// hanging in the nave. The tessellation is chosen for the triangle count (about 262,000), as the
// paper's scene's counts come from its modelling.
Scene atriumScene() {
  Scene scene;
  scene.name = "atrium";
  const int floor = addMaterial(scene, sandstoneFloor());
  const int stone = addMaterial(scene, matte("limestone", glm::vec3(0.5f, 0.45f, 0.37f)));
  const int cloths[3] = {addMaterial(scene, glitterCloth("red curtain", glm::vec3(0.25f, 0.02f, 0.02f))),
                         addMaterial(scene, glitterCloth("green curtain", glm::vec3(0.02f, 0.14f, 0.035f))),
                         addMaterial(scene, glitterCloth("blue curtain", glm::vec3(0.025f, 0.04f, 0.22f)))};

  constexpr float kHalfNave = 5.0f;   // column centres at x = +-5
  constexpr float kBay = 4.0f;        // column spacing along z
  constexpr int kBays = 8;
  constexpr float kStart = -0.5f * kBay * kBays;  // the first column's z
  constexpr float kAisleWall = 9.0f;  // inner face of the outer walls
  struct Storey {
    float floor;        // where its columns stand
    float columnHeight;  // to the top of the abacus: the arches' springing line
    float radius;       // the shaft's
    float archRadius;
    float wallTop;      // the arcade wall's top
    float thickness;    // of the arcade wall
  };
  constexpr Storey kStoreys[2] = {{0.0f, 4.2f, 0.3f, 1.5f, 6.45f, 0.7f}, {6.75f, 3.1f, 0.22f, 1.6f, 12.3f, 0.5f}};
  constexpr float kCornice = 0.3f;    // the band over each arcade wall
  const glm::vec3 along(0, 0, 1);

  // The floor runs out through the far arch.
  scene.meshes.push_back(makeQuad("floor", floor, glm::vec3(0.0f, 0.0f, -6.0f), {kAisleWall + 0.3f, 0, 0}, {0, 0, 24.0f},
                                  glm::vec2(2.0f * (kAisleWall + 0.3f), 48.0f)));
  for (float side : {-1.0f, 1.0f}) {
    const glm::vec3 towardsNave(-side, 0.0f, 0.0f);
    for (int level = 0; level < 2; ++level) {
      const Storey& storey = kStoreys[level];
      const float springing = storey.floor + storey.columnHeight;
      for (int k = 0; k <= kBays; ++k) {
        addColumn(scene, stone, glm::vec3(side * kHalfNave, storey.floor, kStart + kBay * static_cast<float>(k)),
                  storey.columnHeight, storey.radius, 40, 48);
      }
      for (int k = 0; k < kBays; ++k) {
        const float z0 = kStart + kBay * static_cast<float>(k);
        const glm::vec3 front(side * (kHalfNave - 0.5f * storey.thickness), 0.0f, z0);
        const glm::vec3 back(side * (kHalfNave + 0.5f * storey.thickness), 0.0f, z0);
        scene.meshes.push_back(archedWallFace(stone, front, along, towardsNave, kBay, storey.archRadius, springing,
                                              storey.wallTop, 48, 4));
        scene.meshes.push_back(archedWallFace(stone, back, along, -towardsNave, kBay, storey.archRadius, springing,
                                              storey.wallTop, 48, 4));
        scene.meshes.push_back(archIntrados(stone, front, along, -towardsNave, kBay, storey.archRadius, springing,
                                            storey.thickness, 32));
      }
      // The cornice over the arcade, and the floor (gallery) or roof of the aisle behind it.
      const float halfLength = 0.5f * kBay * kBays + 0.5f;
      scene.meshes.push_back(makeBox("cornice", stone,
                                     glm::vec3(side * kHalfNave, storey.wallTop + 0.5f * kCornice, 0.0f),
                                     glm::vec3(0.5f * storey.thickness + 0.15f, 0.5f * kCornice, halfLength), 1.0f));
      const float slabTop = storey.wallTop + kCornice;
      scene.meshes.push_back(makeBox(level == 0 ? "gallery floor" : "aisle roof", stone,
                                     glm::vec3(side * 0.5f * (kHalfNave + kAisleWall), slabTop - 0.15f, 0.0f),
                                     glm::vec3(0.5f * (kAisleWall - kHalfNave), 0.15f, halfLength), 1.0f));
      // Curtains hang between the columns of every other bay, alternating with the other storey.
      for (int k = level; k < kBays; k += 2) {
        const float z = kStart + kBay * (static_cast<float>(k) + 0.5f);
        const float width = kBay - 2.0f * 1.6f * storey.radius;
        const float bottom = storey.floor + 0.15f;
        const float offset = kHalfNave - 0.5f * storey.thickness - 0.25f;
        const int colour = (k + (side > 0.0f ? 1 : 0)) % 3;
        scene.meshes.push_back(curtain(cloths[colour], glm::vec3(side * offset, 0.0f, z), along, towardsNave, width,
                                       springing - 0.2f - bottom, bottom, 0.06f, 0.4f, {72, 40}));
      }
    }
    // The outer wall of the aisles, up to the roof.
    scene.meshes.push_back(makeBox("aisle wall", stone, glm::vec3(side * (kAisleWall + 0.15f), 6.6f, 0.0f),
                                   glm::vec3(0.15f, 6.6f, 0.5f * kBay * kBays + 0.5f), 1.0f));
  }
  // The far wall, with a great arch onto the open ground beyond.
  const float farWall = kStart - 0.6f;
  const float wallTop = kStoreys[1].wallTop + kCornice;
  const glm::vec3 farCorner(-(kAisleWall + 0.3f), 0.0f, farWall);
  const glm::vec3 across(1, 0, 0);
  constexpr float kGreatArch = 2.6f;
  constexpr float kGreatSpringing = 5.0f;
  const float farSpan = 2.0f * (kAisleWall + 0.3f);
  scene.meshes.push_back(archedWallFace(stone, farCorner, across, along, farSpan, kGreatArch, kGreatSpringing, wallTop, 96, 8));
  scene.meshes.push_back(archedWallFace(stone, farCorner - glm::vec3(0.0f, 0.0f, 0.8f), across, -along, farSpan, kGreatArch,
                                        kGreatSpringing, wallTop, 96, 8));
  scene.meshes.push_back(archIntrados(stone, farCorner, across, -along, farSpan, kGreatArch, kGreatSpringing, 0.8f, 48));
  // The wall below the springing line on either side of the great arch.
  for (float side : {-1.0f, 1.0f}) {
    const float halfWidth = 0.5f * (kAisleWall + 0.3f - kGreatArch);
    scene.meshes.push_back(makeBox("far wall", stone, glm::vec3(side * (kGreatArch + halfWidth), 0.5f * kGreatSpringing, farWall - 0.4f),
                                   glm::vec3(halfWidth, 0.5f * kGreatSpringing, 0.4f), 1.0f));
  }

  // A high sun from the front left lights the right-hand arcade and half the floor; three warm lamps
  // hang low over the nave, their mirror images on the floor in the lower half of the default view.
  scene.lights.push_back(directionalLight({0.45f, -1.0f, 0.35f}, glm::vec3(1.6f, 1.5f, 1.35f)));
  for (float z : {6.0f, -4.0f, -14.0f}) scene.lights.push_back(pointLight({0.0f, 2.8f, z}, glm::vec3(40.0f, 33.0f, 24.0f)));
  scene.environment = sky(0.25f);
  scene.exposure = 0.6f;

  setCameras(scene, camera({0.0f, 1.6f, 14.5f}, {0.0f, 3.0f, -16.0f}, 55.0f));
  scene.cameras["floor"] = camera({0.8f, 1.0f, 8.0f}, {0.0f, 0.0f, 3.0f}, 50.0f);
  scene.cameras["curtain"] = camera({0.5f, 2.0f, 5.0f}, {4.4f, 2.0f, -1.0f}, 50.0f);
  scene.cameras["gallery"] = camera({-7.0f, 8.5f, 14.0f}, {2.0f, 4.0f, -8.0f}, 60.0f);
  return scene;
}

// The car: after the Citroen 2CV of Chermain et al. 2020's performance table (704,527 triangles),
// glint's own geometry of the same size. A rounded body with its cabin lofted from superellipse
// sections, in metallic flake paint whose glints take random colours; tinted glass in the
// windscreen, the side and rear windows; four wheels with tyres and dished rims; round headlamps and
// chrome bumpers; on a concrete floor under a sun whose mirror image lies on the bonnet, the sky,
// and a point light low in front of the flank whose mirror image runs along the doors as seen from
// the default camera. The body's tessellation is chosen for the triangle count (about 705,000).
Scene carScene() {
  Scene scene;
  scene.name = "car";
  // The car paint with sparser flakes (log density 8 instead of 12): a few dozen to a pixel at the
  // default view, so that they sparkle.
  Material flakePaint = carPaint();
  flakePaint.glint.logDensity = 8.0f;
  const int paint = addMaterial(scene, flakePaint);
  const int floor = addMaterial(scene, plainGrey("concrete", 0.3f));
  Material glassMaterial = matte("glass", glm::vec3(0.015f, 0.02f, 0.025f));
  glassMaterial.roughness = 0.1f;
  const int glass = addMaterial(scene, glassMaterial);
  const int rubber = addMaterial(scene, plainGrey("tyre", 0.03f));
  Material rimMaterial = plainGrey("rim", 0.7f);
  rimMaterial.metallic = 1.0f;
  rimMaterial.roughness = 0.35f;
  const int rim = addMaterial(scene, rimMaterial);
  Material chromeMaterial = plainGrey("chrome", 0.9f);
  chromeMaterial.metallic = 1.0f;
  chromeMaterial.roughness = 0.2f;
  const int chrome = addMaterial(scene, chromeMaterial);
  Material lampMaterial = plainGrey("headlamp", 0.8f);
  lampMaterial.emissive = glm::vec3(0.9f, 0.85f, 0.7f);
  const int lamp = addMaterial(scene, lampMaterial);

  const CarBody body;
  Mesh shell = makeSurfaceFromPositions(
      "car body", paint, 616, 548, true, [&](float s, float t) { return body.position(s, t); },
      [&](float s, float) { return body.axis(s); },
      [&](float s, float) { return glm::vec3(s < 0.5f ? -1.0f : 1.0f, 0.0f, 0.0f); },
      CarPaintUv(body));
  const Mesh& shape = shell;
  scene.meshes.push_back(splitOffTriangles(shell, "car windows", glass, [&](std::size_t triangle) {
    const Vertex& a = shape.vertices[shape.indices[3 * triangle]];
    const Vertex& b = shape.vertices[shape.indices[3 * triangle + 1]];
    const Vertex& c = shape.vertices[shape.indices[3 * triangle + 2]];
    return carWindow(body, (a.position + b.position + c.position) / 3.0f, glm::normalize(a.normal + b.normal + c.normal));
  }));
  scene.meshes.push_back(std::move(shell));

  constexpr float kWheelRadius = 0.32f;
  for (float x : {-1.2f, 1.2f}) {
    for (float side : {-1.0f, 1.0f}) {
      addWheel(scene, rubber, rim, glm::vec3(x, kWheelRadius, side * 0.72f), glm::vec3(0.0f, 0.0f, side), kWheelRadius);
    }
  }
  for (float side : {-1.0f, 1.0f}) {
    scene.meshes.push_back(makeUvSphere("headlamp", lamp, glm::vec3(1.84f, 0.64f, side * 0.36f), 0.08f, 32, 16));
  }
  for (float end : {-1.0f, 1.0f}) {
    scene.meshes.push_back(makeBox("bumper", chrome, glm::vec3(end * 1.86f, 0.46f, 0.0f), glm::vec3(0.04f, 0.035f, 0.5f), 1.0f));
  }
  scene.meshes.push_back(makeQuad("floor", floor, glm::vec3(0.0f), {30, 0, 0}, {0, 0, 30}, glm::vec2(60.0f)));

  scene.lights.push_back(directionalLight({-0.4f, -1.0f, -0.55f}, glm::vec3(2.6f, 2.5f, 2.3f)));
  scene.lights.push_back(pointLight({-1.0f, 0.7f, 3.2f}, glm::vec3(20.0f)));
  scene.environment = sky(0.35f);
  setCameras(scene, camera({4.2f, 1.6f, 3.8f}, {0.0f, 0.65f, 0.0f}, 36.0f));
  scene.cameras["side"] = camera({0.0f, 1.1f, 7.0f}, {0.0f, 0.8f, 0.0f}, 40.0f);
  scene.cameras["bonnet"] = camera({2.9f, 1.5f, 1.6f}, {1.2f, 0.8f, 0.0f}, 40.0f);
  return scene;
}

// The benchmark's worst case: a grazing view of a large glittering plane (snow or stone), where
// footprints are long and thin (anisotropy clamped to 8) and far cells are large, so a pixel
// visits the most cells. The sun sits low behind the plane, so its glitter band runs to the
// horizon across the whole view.
Scene grazingPlaneScene(const char* name, float alpha) {
  Scene scene;
  scene.name = name;
  constexpr float kSize = 200.0f;
  Material snow;
  snow.name = "glittering plane";
  snow.baseColour = glm::vec4(0.55f, 0.57f, 0.6f, 1.0f);
  snow.metallic = 0.0f;
  snow.roughness = roughnessFor(alpha);
  snow.glint = glintLayer(alpha, 14.0f, kSize);  // one glint-uv unit per metre
  const int material = addMaterial(scene, snow);
  scene.meshes.push_back(makeQuad("plane", material, glm::vec3(0.0f), {0.5f * kSize, 0, 0}, {0, 0, 0.5f * kSize}));
  scene.lights.push_back(directionalLight({0.0f, -0.25f, 1.0f}, glm::vec3(3.0f)));
  scene.environment = sky(0.3f);
  setCameras(scene, camera({0.0f, 1.2f, 8.0f}, {0.0f, 0.2f, -20.0f}, 50.0f));
  return scene;
}

Scene grazingSmoothScene() { return grazingPlaneScene("grazing-smooth", 0.1f); }
Scene grazingRoughScene() { return grazingPlaneScene("grazing-rough", 0.5f); }

// The showcase for glint anti-aliasing and normal-map filtering, after the arctic teaser of
// Chermain et al. 2021: a 64 x 64 m snow field whose tiling normal map (one 1.6 m tile, 256
// texels, repeated 40 times) shrinks to many texels per pixel in the distance, a snowman and a
// silver snowflake ornament of thin rings, a low sun ahead whose glitter band runs to the horizon.
Scene arcticScene() {
  Scene scene;
  scene.name = "arctic";
  constexpr float kField = 64.0f;
  const float tiles = kField / static_cast<float>(kSnowTileMetres);
  const int normalMap = addTexture(scene, snowNormalMap());
  Material field = snow("snow field", 0.05f, kSnowGlintUvPerMetre * static_cast<float>(kSnowTileMetres));  // uv in tiles
  field.normalTexture = normalMap;
  const int snowField = addMaterial(scene, field);
  const int snowBalls = addMaterial(scene, snow("snowman snow", 0.2f, kSnowGlintUvPerMetre));  // uv in metres
  const int silver = addMaterial(scene, sparklySilver());
  const int coal = addMaterial(scene, plainGrey("coal", 0.03f));
  const int carrot = addMaterial(scene, matte("carrot", glm::vec3(0.8f, 0.25f, 0.03f)));

  // The field runs from 8 m behind the camera to 56 m ahead of it.
  const glm::vec3 cameraPosition(0.0f, 1.6f, 5.0f);
  scene.meshes.push_back(makeQuad("snow field", snowField, glm::vec3(0.0f, 0.0f, -24.0f), {0.5f * kField, 0, 0},
                                  {0, 0, 0.5f * kField}, glm::vec2(tiles)));
  auto facingCamera = [&](glm::vec3 at) {
    return glm::normalize(glm::vec3(cameraPosition.x - at.x, 0.0f, cameraPosition.z - at.z));
  };
  const glm::vec3 snowmanAt(1.3f, 0.0f, -2.0f);
  addSnowman(scene, snowBalls, coal, carrot, snowmanAt, facingCamera(snowmanAt));
  const glm::vec3 ornamentAt(-1.1f, 0.0f, -0.8f);
  const glm::vec3 ornamentCentre = addSnowflakeOrnament(scene, silver, ornamentAt, facingCamera(ornamentAt), glm::radians(20.0f));

  // The low sun, 16 degrees left of the view axis (-z), 12 degrees up: its glitter band runs from
  // the horizon to the bottom left of the default view. The objects stand between the camera and
  // the sun, lit from behind, where a thin tube shows the sun's highlight only in slivers under a
  // pixel wide; so a cool fill from behind the camera, standing in for the bright sky there (the
  // environment lights without glints), makes the snowman and the ornament glitter. Its mirror
  // image on the snow lies behind the camera.
  scene.lights.push_back(directionalLight(-horizonDirection(16.0f, 12.0f), glm::vec3(6.0f, 5.6f, 5.0f)));
  scene.lights.push_back(directionalLight(-horizonDirection(160.0f, 30.0f), glm::vec3(1.5f, 1.65f, 1.9f)));
  scene.environment = sky(0.4f);
  setCameras(scene, camera(cameraPosition, {0.0f, 0.6f, -2.0f}));
  scene.cameras["ornament"] = camera(ornamentCentre + 2.2f * facingCamera(ornamentAt) + glm::vec3(0.0f, 0.3f, 0.0f), ornamentCentre);
  return scene;
}

struct BuiltinScene {
  const char* name;
  Scene (*make)();
};

constexpr BuiltinScene kBuiltinScenes[] = {
    {"sphere", sphereScene},
    {"parquet", parquetScene},
    {"carpaint", carpaintScene},
    {"showroom", showroomScene},
    {"grazing-smooth", grazingSmoothScene},
    {"grazing-rough", grazingRoughScene},
    {"arctic", arcticScene},
    {"atrium", atriumScene},
    {"car", carScene},
};

std::string joinedNames() {
  std::string names;
  for (const BuiltinScene& scene : kBuiltinScenes) names += (names.empty() ? "" : ", ") + std::string(scene.name);
  return names;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinScene& scene : kBuiltinScenes) names.emplace_back(scene.name);
  return names;
}

bool isBuiltinScene(const std::string& name) {
  return std::any_of(std::begin(kBuiltinScenes), std::end(kBuiltinScenes),
                     [&](const BuiltinScene& scene) { return name == scene.name; });
}

Scene makeBuiltinScene(const std::string& name) {
  for (const BuiltinScene& scene : kBuiltinScenes) {
    if (name == scene.name) return scene.make();
  }
  throw Error("unknown built-in scene '" + name + "' (built-in: " + joinedNames() + ")");
}

Environment skyEnvironment(float intensity) { return sky(intensity); }

Scene loadScene(const std::string& nameOrPath) {
  if (isBuiltinScene(nameOrPath)) return makeBuiltinScene(nameOrPath);
  std::error_code ignored;
  if (!nameOrPath.empty() && std::filesystem::exists(nameOrPath, ignored)) return loadGltf(nameOrPath);
  throw Error("unknown scene '" + nameOrPath + "' (built-in: " + joinedNames() + ") and no such file");
}

std::string sceneName(const std::string& nameOrPath) {
  return isBuiltinScene(nameOrPath) ? nameOrPath : std::filesystem::path(nameOrPath).stem().string();
}

}  // namespace glint::scene
