// The real-time renderer on the headless context: golden images of the built-in scenes,
// convergence to Cook-Torrance at very high density, determinism, no GL errors.
#include <cmath>
#include <algorithm>
#include <cstdlib>

#include <functional>
#include <map>

#include <gtest/gtest.h>

#include "gl/renderer.h"
#include "gl/shadow_maps.h"
#include "gl_support.h"
#include "glint/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/geometry.h"
#include "test_support.h"
#include "trace/camera.h"
#include "trace/environment.h"

namespace glint {
namespace {

using namespace glint::test;

constexpr int kSize = 256;

// The 2020 model unless told otherwise: the properties below (and the golden images) are the
// model's; the anti-aliasing's own tests say which mode they render.
ImageRgbF render(const scene::Scene& scene, SpecularModel brdf, int spp = 1,
                 gl::AntiAliasing antiAliasing = gl::AntiAliasing::None) {
  useGlContext();
  gl::Renderer renderer(scene, defaultDictionary());
  gl::FrameSettings frame;
  frame.width = kSize;
  frame.height = kSize;
  frame.brdf = brdf;
  frame.antiAliasing = antiAliasing;
  frame.camera = scene.cameras.at("default");
  ImageRgbF image = gl::renderSupersampled(renderer, frame, spp);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << scene.name;
  return image;
}

// Every glint layer at the given density with all cells holding microfacets (relative area 1:
// the model converges to Cook-Torrance only then; with MRA < 1 to MRA times it).
scene::Scene withLogDensity(scene::Scene scene, float logDensity) {
  for (scene::Material& m : scene.materials) {
    m.glint.logDensity = logDensity;
    m.glint.relativeArea = 1.0f;
  }
  return scene;
}

std::filesystem::path goldenPath(const std::string& name) {
  return std::filesystem::path(GLINT_SOURCE_DIR) / "tests" / "golden" / (name + ".png");
}

// ---- shadow cascades (no OpenGL needed: the maps' matrices) ------------------------------------

TEST(ShadowCascades, SplitsMixLogarithmicAndUniform) {
  // Near 1, far 100, two cascades: the logarithmic split is at 10, the uniform one at 50.5, and
  // the practical scheme weighs them 0.75 and 0.25: 20.125.
  const std::vector<float> splits = gl::cascadeSplits(1.0f, 100.0f, 2);
  ASSERT_EQ(splits.size(), 3u);
  EXPECT_FLOAT_EQ(splits[0], 1.0f);
  EXPECT_NEAR(splits[1], 20.125f, 1e-3f);
  EXPECT_FLOAT_EQ(splits[2], 100.0f);
}

// The arctic's sun, seen from its default camera moved by `offset` (a 128 x 128 frame).
std::vector<gl::ShadowLookup> arcticSunCascades(glm::vec3 offset, int cascades = gl::kShadowCascades) {
  const scene::Scene arctic = scene::makeBuiltinScene("arctic");
  scene::Camera camera = arctic.cameras.at("default");
  camera.position += offset;
  camera.target += offset;
  gl::ShadowView view;
  view.viewProjection = gl::viewProjection(camera, 128, 128, glm::vec2(0.0f), arctic.boundsMin(), arctic.boundsMax());
  view.cameraPosition = camera.position;
  view.cascades = cascades;
  return gl::shadowLookups(arctic.lights.at(0), arctic.boundsMin(), arctic.boundsMax(), view);
}

TEST(ShadowCascades, NearCascadesHaveFinerTexelsThanTheWholeScenesMap) {
  const std::vector<gl::ShadowLookup> whole = arcticSunCascades(glm::vec3(0.0f), 1);
  const std::vector<gl::ShadowLookup> cascades = arcticSunCascades(glm::vec3(0.0f));
  ASSERT_EQ(whole.size(), 1u);
  ASSERT_EQ(cascades.size(), static_cast<std::size_t>(gl::kShadowCascades));
  std::printf("arctic sun: one map %.2f mm texels; cascades", 1e3 * whole[0].texel);
  for (const gl::ShadowLookup& c : cascades) std::printf(" %.2f", 1e3 * c.texel);
  std::printf(" mm\n");
  for (std::size_t c = 1; c < cascades.size(); ++c) EXPECT_GE(cascades[c].texel, cascades[c - 1].texel);
  EXPECT_LE(cascades.back().texel, whole[0].texel);
  // The ornament's rings (6 cm) cast their shadows 3 to 5 m from the camera: the second cascade's.
  EXPECT_LT(cascades[1].texel, 0.1f * whole[0].texel);
}

TEST(ShadowCascades, ACameraThatMovesALittleKeepsEachCascadesTexelGrid) {
  // A fixed point falls on the same place in a texel of each cascade as the camera moves by a few
  // millimetres at a time (the cascade's size is kept, its centre moves by whole texels), so a
  // shadow's filtered edge does not crawl; the scene's texel positions differ by whole numbers.
  const glm::vec3 point(-1.1f, 0.3f, -0.8f);  // at the arctic's ornament
  const std::vector<gl::ShadowLookup> start = arcticSunCascades(glm::vec3(0.0f));
  int kept = 0;
  for (int step = 1; step <= 20; ++step) {
    const std::vector<gl::ShadowLookup> moved = arcticSunCascades(glm::vec3(0.003f, 0.001f, -0.002f) * float(step));
    for (std::size_t c = 0; c < start.size(); ++c) {
      if (moved[c].texel != start[c].texel) continue;  // crossed a 2^(1/8) step of the cascade's size
      ++kept;
      auto texelPosition = [&](const gl::ShadowLookup& lookup) {
        const glm::vec4 clip = lookup.matrix * glm::vec4(point, 1.0f);
        return (0.5f * glm::vec2(clip) + 0.5f) * static_cast<float>(gl::kShadowMapSize);
      };
      const glm::vec2 shift = texelPosition(moved[c]) - texelPosition(start[c]);
      EXPECT_NEAR(shift.x, std::round(shift.x), 2e-2f) << "step " << step << ", cascade " << c;
      EXPECT_NEAR(shift.y, std::round(shift.y), 2e-2f) << "step " << step << ", cascade " << c;
    }
  }
  EXPECT_GT(kept, 60);  // most of the 80 moved cascades kept their size
}

TEST(RenderGl, VeryHighDensityGlintEqualsCookTorrance) {
  // At log density 80 every cell is in the smooth limit (see GlintBrdf.ConvergesToCookTorrance...):
  // the two renders differ by float rounding only. Bound: RMSE under 0.5% of the mean, far above
  // rounding and far below what one glint pixel more or less gives at 256 x 256.
  for (const std::string& name : scene::builtinSceneNames()) {
    const scene::Scene scene = withLogDensity(scene::makeBuiltinScene(name), 80.0f);
    const ImageError error = compareImages(render(scene, SpecularModel::Glint), render(scene, SpecularModel::CookTorrance));
    EXPECT_LT(error.rmse, 0.005 * error.meanReference) << name << ": rmse " << error.rmse << ", mean " << error.meanReference;
    std::printf("%s at log density 80: glint vs Cook-Torrance RMSE / mean = %.2e\n", name.c_str(),
                error.rmse / error.meanReference);
  }
}

TEST(RenderGl, NormalMapFilteringChangesNothingOnAConstantNormalMap) {
  // The arctic snow with its normal map replaced by one tilted normal: ggaa+lean must render what
  // ggaa renders (no covariance, the same mean normal), within float rounding; with the real map
  // it must not (the filter has something to do there).
  scene::Scene arctic = scene::makeBuiltinScene("arctic");
  scene::Scene flat = arctic;
  for (scene::Material& m : flat.materials) {
    if (m.normalTexture < 0) continue;
    scene::Texture& t = flat.textures[static_cast<std::size_t>(m.normalTexture)];
    for (std::size_t i = 0; i < t.rgba.size(); i += 4) {
      t.rgba[i] = 150;
      t.rgba[i + 1] = 110;
      t.rgba[i + 2] = 240;
    }
  }
  const ImageError constant = compareImages(render(flat, SpecularModel::Glint, 1, gl::AntiAliasing::GgaaLean),
                                            render(flat, SpecularModel::Glint, 1, gl::AntiAliasing::Ggaa));
  EXPECT_LT(constant.relmse, 1e-8) << "rmse " << constant.rmse;
  const ImageError real = compareImages(render(arctic, SpecularModel::Glint, 1, gl::AntiAliasing::GgaaLean),
                                        render(arctic, SpecularModel::Glint, 1, gl::AntiAliasing::Ggaa));
  EXPECT_GT(real.relmse, 1e-3);
  std::printf("ggaa+lean against ggaa: relMSE %.2e on a constant normal map, %.2e on the arctic's\n", constant.relmse,
              real.relmse);
}

TEST(RenderGl, DefaultDensityShowsGlints) {
  // At each scene's own density the glint render must differ visibly from Cook-Torrance: an RMSE
  // above 5% of the mean pixel value (measured: docs/renderer.md).
  for (const std::string& name : scene::builtinSceneNames()) {
    const scene::Scene scene = scene::makeBuiltinScene(name);
    const ImageError error = compareImages(render(scene, SpecularModel::Glint), render(scene, SpecularModel::CookTorrance));
    EXPECT_GT(error.rmse, 0.05 * error.meanReference) << name << ": rmse " << error.rmse << ", mean " << error.meanReference;
    std::printf("%s at its own density: glint vs Cook-Torrance RMSE / mean = %.3f\n", name.c_str(),
                error.rmse / error.meanReference);
  }
}

// The glint layer's correlation between each pixel of an annulus around `centre` and the point
// `lag` pixels further out along the radius, and the same across it (along the circle), both
// relative to the layer's variance over the annulus; bilinear between pixel centres. Radial streaks
// raise the first and not the second.
struct StreakCorrelation {
  double radial;
  double tangential;
};
StreakCorrelation streakCorrelation(const std::vector<double>& layer, int width, glm::vec2 centre, float innerRadius,
                                    float outerRadius, float lag) {
  auto at = [&](glm::vec2 p) {
    const glm::vec2 q = p - glm::vec2(0.5f);
    const glm::ivec2 i = glm::ivec2(glm::floor(q));
    const glm::vec2 f = q - glm::floor(q);
    auto v = [&](int x, int y) { return layer[static_cast<std::size_t>(y) * width + x]; };
    return (1 - f.x) * (1 - f.y) * v(i.x, i.y) + f.x * (1 - f.y) * v(i.x + 1, i.y) + (1 - f.x) * f.y * v(i.x, i.y + 1) +
           f.x * f.y * v(i.x + 1, i.y + 1);
  };
  std::vector<glm::vec2> points;
  double mean = 0.0;
  for (int y = 0; y < width; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::vec2 p(x + 0.5f, y + 0.5f);
      const float r = glm::length(p - centre);
      if (r < innerRadius || r >= outerRadius) continue;
      points.push_back(p);
      mean += at(p);
    }
  }
  mean /= double(points.size());
  double variance = 0.0, radial = 0.0, tangential = 0.0;
  for (glm::vec2 p : points) {
    const glm::vec2 out = glm::normalize(p - centre);
    const double v = at(p) - mean;
    variance += v * v;
    radial += v * (at(p + lag * out) - mean);
    tangential += v * (at(p + lag * glm::vec2(-out.y, out.x)) - mean);
  }
  return {radial / variance, tangential / variance};
}

TEST(RenderGl, NoRadialStreaksAtTheUvSpherePole) {
  // The built-in sphere seen straight down onto its pole from 1 m (0.6 m across the frame), lit
  // from near the camera. Around the pole u's derivative is up to 10 times v's, and the screen axes
  // turn around it: where they stand at 45 degrees to the meridians the footprint's two derivatives
  // are equally long, and taking the shorter as the ellipse's minor axis chose cells up to 7 times
  // longer along the meridian than a pixel (Footprint.UvSpherePoleFootprintHas...). Neighbouring
  // pixels along a meridian then share cells: a starburst of radial streaks. In the glint layer
  // (glint minus Cook-Torrance, luminance) out to 48 pixels (about 0.11 m, colatitude 6.5
  // degrees), the correlation 2 pixels along the radius may exceed that across it by at most 0.15.
  scene::Scene scene = scene::makeBuiltinScene("sphere");
  scene.lights.clear();
  scene::Light light;
  light.type = scene::Light::Type::Point;
  light.position = glm::vec3(0.4f, 3.0f, 0.3f);
  light.intensity = glm::vec3(8.0f);
  scene.lights.push_back(light);
  scene::Camera camera;
  camera.position = glm::vec3(0.0f, 2.0f, 0.0f);
  camera.target = glm::vec3(0.0f, 1.0f, 0.0f);
  camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
  camera.verticalFovDegrees = 2.0f * glm::degrees(std::atan(0.3f));
  scene.cameras["default"] = camera;
  const ImageRgbF glint = render(scene, SpecularModel::Glint);
  const ImageRgbF smooth = render(scene, SpecularModel::CookTorrance);
  auto luminance = [](glm::vec3 c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };  // Rec. 709
  std::vector<double> layer(glint.pixels.size());
  for (std::size_t i = 0; i < layer.size(); ++i) layer[i] = luminance(glint.pixels[i]) - luminance(smooth.pixels[i]);
  const glm::vec2 pole(0.5f * kSize);  // the camera looks straight at it
  const StreakCorrelation nearPole = streakCorrelation(layer, kSize, pole, 4.0f, 48.0f, 2.0f);
  const StreakCorrelation further = streakCorrelation(layer, kSize, pole, 48.0f, 120.0f, 2.0f);
  std::printf("glint layer's correlation at 2 pixels, along / across the radius: %.3f / %.3f within 48 pixels of the "
              "pole, %.3f / %.3f from 48 to 120\n",
              nearPole.radial, nearPole.tangential, further.radial, further.tangential);
  EXPECT_LT(nearPole.radial - nearPole.tangential, 0.15);
}

TEST(RenderGl, EveryBrdfRendersEveryBenchmarkSceneWithoutGlErrors) {
  // A correctness test, not a timing test: `glint bench` times every built-in scene with every
  // model; each frame must render without a GL error and with finite radiance.
  for (const std::string& name : scene::builtinSceneNames()) {
    const scene::Scene scene = scene::makeBuiltinScene(name);
    for (SpecularModel model : allSpecularModels()) {
      const ImageRgbF image = render(scene, model);  // checks glGetError
      const bool finite = std::all_of(image.pixels.begin(), image.pixels.end(), [](const glm::vec3& p) {
        return std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b);
      });
      EXPECT_TRUE(finite) << name << " with " << toString(model);
    }
  }
}

// The glint programs evaluate all of a pixel's lights over one walk of the footprint's cells, with
// the light count compiled in (LIGHT_COUNT): radiance is still linear in the lights, so a frame lit
// by the first k lights, minus the unlit frame, must be the sum of the frames lit by each of them.
// Counts 0, 1, 2, 3 and the renderer's largest, 8 (each count is a program compiled by llvmpipe in
// about a second, so not all nine). A light given another light's P22 would break the sum at its
// glints. The bound, 1e-4 of the pixel's magnitude, is far above the float rounding
// of summing nine frames (about 1e-6) and far below a misplaced glint.
TEST(RenderGl, LightsAddUp) {
  useGlContext();
  const scene::Scene showroom = scene::makeBuiltinScene("showroom");  // coloured and plain glints
  std::vector<scene::Light> lights = showroom.lights;
  const glm::vec3 extraPositions[] = {{-1.0f, 2.5f, 3.0f}, {2.5f, 0.8f, 1.5f}, {0.0f, 4.0f, -1.0f}, {-3.0f, 1.0f, 1.0f}};
  for (const glm::vec3& position : extraPositions) {
    scene::Light light = lights.front();
    light.position = position;
    lights.push_back(light);
  }
  scene::Light sun;
  sun.type = scene::Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.6f));
  sun.intensity = glm::vec3(0.7f);
  lights.push_back(sun);
  ASSERT_EQ(lights.size(), 8u);

  gl::Renderer renderer(showroom, defaultDictionary());
  gl::FrameSettings frame;
  frame.width = 128;
  frame.height = 128;
  frame.brdf = SpecularModel::Glint;
  frame.camera = showroom.cameras.at("default");
  auto litBy = [&](std::vector<scene::Light> subset) {
    renderer.lights() = std::move(subset);
    ImageRgbF image = gl::renderSupersampled(renderer, frame, 1);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR)) << renderer.lights().size() << " lights";
    return image;
  };
  const ImageRgbF unlit = litBy({});
  std::vector<ImageRgbF> alone;
  for (const scene::Light& light : lights) alone.push_back(litBy({light}));
  double largest = 0.0;
  for (const std::size_t count : {std::size_t{2}, std::size_t{3}, lights.size()}) {
    const ImageRgbF together = litBy(std::vector<scene::Light>(lights.begin(), lights.begin() + count));
    int wrong = 0;
    for (std::size_t p = 0; p < unlit.pixels.size(); ++p) {
      for (int c = 0; c < 3; ++c) {
        double sum = unlit.pixels[p][c];
        double magnitude = std::abs(unlit.pixels[p][c]);
        for (std::size_t j = 0; j < count; ++j) {
          sum += alone[j].pixels[p][c] - unlit.pixels[p][c];
          magnitude += std::abs(alone[j].pixels[p][c]);
        }
        const double difference = std::abs(together.pixels[p][c] - sum);
        largest = std::max(largest, difference / (magnitude + 1e-6));
        wrong += difference > 1e-4 * magnitude + 1e-6;
      }
    }
    EXPECT_EQ(wrong, 0) << count << " lights";
  }
  std::printf("lights add up: largest difference %.2e of the pixel's magnitude (bound 1e-4)\n", largest);
}

// The grazing plane seen straight down from 3 m through a 45-degree field of view, 128 x 128,
// glint BRDF, for the tests of a single light's falloff: each frame is rendered under the lights
// given, and a pixel's floor point lies at its horizontal distance (floorDistance) from the point
// below the camera, whatever the image's orientation.
class TopDownPlane {
 public:
  static constexpr float kCameraHeight = 3.0f;
  static constexpr int kSide = 128;

  TopDownPlane() : scene_(scene::makeBuiltinScene("grazing-smooth")), renderer_(scene_, defaultDictionary()) {
    frame_.width = kSide;
    frame_.height = kSide;
    frame_.brdf = SpecularModel::Glint;
    frame_.camera.position = glm::vec3(0.0f, kCameraHeight, 0.0f);
    frame_.camera.target = glm::vec3(0.0f);
    frame_.camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
    frame_.camera.verticalFovDegrees = 45.0f;
  }

  ImageRgbF litBy(std::vector<scene::Light> lights) {
    renderer_.lights() = std::move(lights);
    ImageRgbF image = gl::renderSupersampled(renderer_, frame_, 1);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    return image;
  }

  static double floorDistance(int x, int y) {
    const double halfHeight = kCameraHeight * std::tan(0.5 * 45.0 * 3.14159265358979 / 180.0);
    const double nx = 2.0 * (x + 0.5) / kSide - 1.0;
    const double ny = 2.0 * (y + 0.5) / kSide - 1.0;
    return halfHeight * std::hypot(nx, ny);
  }

 private:
  scene::Scene scene_;
  gl::Renderer renderer_;
  gl::FrameSettings frame_;
};

// A spot light (KHR_lights_punctual's cone) lights the grazing plane like a point light of the
// same intensity within its inner cone, not at all beyond its outer one, and in between something
// between the two. Seen straight down from above the spot, a pixel's floor point and so its angle
// from the spot's axis follow from the camera alone (the frame is symmetric about the axis, so
// the image's orientation does not matter). Pixels within 0.03 radians of a cone are left out.
TEST(RenderGl, SpotLightsLightTheirConeOnly) {
  useGlContext();
  constexpr float kSpotHeight = 1.5f;
  constexpr float kInner = 0.25f;
  constexpr float kOuter = 0.5f;
  scene::Light point;
  point.type = scene::Light::Type::Point;
  point.position = glm::vec3(0.0f, kSpotHeight, 0.0f);
  point.intensity = glm::vec3(2.0f);
  scene::Light spot = point;
  spot.type = scene::Light::Type::Spot;
  spot.direction = glm::vec3(0.0f, -1.0f, 0.0f);
  spot.innerConeAngle = kInner;
  spot.outerConeAngle = kOuter;

  TopDownPlane view;
  const ImageRgbF dark = view.litBy({});
  const ImageRgbF byPoint = view.litBy({point});
  const ImageRgbF bySpot = view.litBy({spot});
  int inside = 0;
  int outside = 0;
  int between = 0;
  for (int y = 0; y < TopDownPlane::kSide; ++y) {
    for (int x = 0; x < TopDownPlane::kSide; ++x) {
      const double angle = std::atan(TopDownPlane::floorDistance(x, y) / kSpotHeight);
      const std::size_t p = static_cast<std::size_t>(y) * TopDownPlane::kSide + x;
      for (int c = 0; c < 3; ++c) {
        const double s = bySpot.pixels[p][c];
        const double full = byPoint.pixels[p][c];
        const double none = dark.pixels[p][c];
        ASSERT_GT(full, none + 1e-4) << "the point light lights pixel " << x << "," << y;
        if (angle < kInner - 0.03) {
          EXPECT_NEAR(s, full, 1e-5 * full) << x << "," << y;
          inside += c == 0;
        } else if (angle > kOuter + 0.03) {
          EXPECT_NEAR(s, none, 1e-5 * none + 1e-7) << x << "," << y;
          outside += c == 0;
        } else if (angle > kInner + 0.03 && angle < kOuter - 0.03) {
          EXPECT_GT(s, none) << x << "," << y;
          EXPECT_LT(s, full) << x << "," << y;
          between += c == 0;
        }
      }
    }
  }
  EXPECT_GT(inside, 500);
  EXPECT_GT(outside, 2000);
  EXPECT_GT(between, 1000);
  std::printf("spot light: %d pixels inside its inner cone, %d between the cones, %d outside\n", inside, between,
              outside);
}

// A point light's range (KHR_lights_punctual) scales its light by the extension's window: seen
// straight down at the grazing plane from above the light, a pixel's floor point, its distance d
// to the light and so the window clamp(1 - (d / range)^4, 0, 1) follow from the camera alone, and
// the light's part of the pixel (lit minus unlit) must be the window times the part the same light
// gives without a range. Pixels within 2% of the range are left out (the window's slope there).
TEST(RenderGl, LightRangeEndsThePointLightAsTheGltfExtensionSays) {
  useGlContext();
  constexpr double kLightHeight = 1.5;
  constexpr double kRange = 1.9;  // reaches the floor out to 1.17 m from below the light; the view, 1.76 m
  scene::Light point;
  point.type = scene::Light::Type::Point;
  point.position = glm::vec3(0.0f, float(kLightHeight), 0.0f);
  point.intensity = glm::vec3(2.0f);
  scene::Light ranged = point;
  ranged.range = float(kRange);

  TopDownPlane view;
  const ImageRgbF dark = view.litBy({});
  const ImageRgbF byPoint = view.litBy({point});
  const ImageRgbF byRanged = view.litBy({ranged});
  int reached = 0;
  int beyond = 0;
  double worst = 0.0;
  for (int y = 0; y < TopDownPlane::kSide; ++y) {
    for (int x = 0; x < TopDownPlane::kSide; ++x) {
      const double d = std::hypot(TopDownPlane::floorDistance(x, y), kLightHeight);
      if (std::abs(d - kRange) < 0.02 * kRange) continue;
      const double window = std::clamp(1.0 - std::pow(d / kRange, 4.0), 0.0, 1.0);
      const std::size_t p = static_cast<std::size_t>(y) * TopDownPlane::kSide + x;
      for (int c = 0; c < 3; ++c) {
        const double none = dark.pixels[p][c];
        const double full = byPoint.pixels[p][c] - none;
        const double got = byRanged.pixels[p][c] - none;
        ASSERT_GT(full, 1e-4) << "the point light lights pixel " << x << "," << y;
        worst = std::max(worst, std::abs(got - window * full) / full);
        EXPECT_NEAR(got, window * full, 1e-4 * full + 1e-7) << x << "," << y << ": d " << d;
      }
      (d < kRange ? reached : beyond) += 1;
    }
  }
  EXPECT_GT(reached, 5000);
  EXPECT_GT(beyond, 3000);
  std::printf("light range: %d pixels within it, %d beyond, worst relative error %.2e (bound 1e-4)\n", reached, beyond,
              worst);
}

// glTF's occlusion strength: the ambient light (environment only, no lights, no emission) of a
// plane whose occlusion texture holds o everywhere is scaled by 1 + strength (o - 1), so against
// strength 0 (no occlusion) every plane pixel keeps exactly that fraction; the sky is untouched.
TEST(RenderGl, OcclusionStrengthScalesTheAmbientLightAsGltfSays) {
  useGlContext();
  constexpr std::uint8_t kTexel = 64;
  const double occlusion = kTexel / 255.0;
  auto render = [&](float strength) {
    scene::Scene scene = scene::makeBuiltinScene("grazing-smooth");
    scene.lights.clear();
    scene.textures.push_back({"occlusion", 1, 1, {kTexel, kTexel, kTexel, 255}, false});
    scene.materials[0].occlusionTexture = static_cast<int>(scene.textures.size()) - 1;
    scene.materials[0].occlusionStrength = strength;
    gl::Renderer renderer(scene, defaultDictionary());
    gl::FrameSettings frame;
    frame.width = 64;
    frame.height = 64;
    frame.brdf = SpecularModel::CookTorrance;
    frame.camera = scene.cameras.at("default");
    ImageRgbF image = gl::renderSupersampled(renderer, frame, 1);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    return image;
  };
  const ImageRgbF open = render(0.0f);
  for (const float strength : {0.5f, 1.0f}) {
    const ImageRgbF occluded = render(strength);
    const double fraction = 1.0 + strength * (occlusion - 1.0);
    int plane = 0;
    int sky = 0;
    for (std::size_t p = 0; p < open.pixels.size(); ++p) {
      const bool isSky = occluded.pixels[p] == open.pixels[p];
      (isSky ? sky : plane) += 1;
      if (isSky) continue;
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(occluded.pixels[p][c], fraction * open.pixels[p][c], 1e-5 * open.pixels[p][c]) << p << " " << strength;
      }
    }
    EXPECT_GT(plane, 1000) << strength;
    EXPECT_GT(sky, 500) << strength;
  }
}

// A scene of emissive quads facing +z, seen by a camera on the z axis, for the visibility tests:
// each quad's emission is far above anything the lights or the environment give, so a pixel shows
// which quad (if any) was shaded there.
struct Sheet {
  float z;
  glm::vec3 emissive;
  bool doubleSided;
};

// `edit` changes the scene before it is drawn.
ImageRgbF renderSheets(const std::vector<Sheet>& sheets, float cameraZ,
                       const std::function<void(scene::Scene&)>& edit = nullptr,
                       SpecularModel brdf = SpecularModel::Glint, std::vector<std::string>* warnings = nullptr) {
  useGlContext();
  scene::Scene scene = scene::makeBuiltinScene("grazing-smooth");  // for its lights and sky
  scene.meshes.clear();
  scene.materials.clear();
  for (const Sheet& sheet : sheets) {
    scene::Material m;
    m.name = "sheet";
    m.emissive = sheet.emissive;
    m.doubleSided = sheet.doubleSided;
    scene.materials.push_back(m);
    // cross(halfV, halfU) = +z: counter-clockwise, a front face, seen from +z.
    scene.meshes.push_back(scene::makeQuad("sheet", static_cast<int>(scene.materials.size()) - 1,
                                           glm::vec3(0.0f, 0.0f, sheet.z), {0, 1, 0}, {1, 0, 0}));
  }
  if (edit) edit(scene);
  gl::Renderer renderer(scene, defaultDictionary());
  if (warnings) *warnings = renderer.warnings();
  gl::FrameSettings frame;
  frame.width = 64;
  frame.height = 64;
  frame.brdf = brdf;
  frame.camera.position = glm::vec3(0.0f, 0.0f, cameraZ);
  frame.camera.target = glm::vec3(0.0f);
  ImageRgbF image = gl::renderSupersampled(renderer, frame, 1);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  return image;
}

// The pixels (of 64 x 64) whose radiance is dominated by `emissive`'s channel: more than 50 in it.
int pixelsShowing(const ImageRgbF& image, int channel) {
  return static_cast<int>(std::count_if(image.pixels.begin(), image.pixels.end(),
                                        [channel](const glm::vec3& p) { return p[channel] > 50.0f; }));
}

// glTF's doubleSided: a single-sided sheet is drawn from the front only, a double-sided one from
// both sides. From 3 m a 2 m sheet covers the middle of the 45-degree view, about 1,100 pixels.
TEST(RenderGl, SingleSidedMaterialsAreDrawnFromTheFrontOnly) {
  const glm::vec3 red(100.0f, 0.0f, 0.0f);
  const int front = pixelsShowing(renderSheets({{0.0f, red, false}}, 3.0f), 0);
  EXPECT_GT(front, 1000);
  EXPECT_EQ(pixelsShowing(renderSheets({{0.0f, red, false}}, -3.0f), 0), 0);
  EXPECT_EQ(pixelsShowing(renderSheets({{0.0f, red, true}}, -3.0f), 0), front);
}

// The depth pre-pass leaves the image that of a single depth-tested pass: the nearest sheet shows
// whatever the order they are drawn in, and of two sheets at the same depth the first drawn shows,
// as under GL_LESS (the shading pass's stencil keeps the first fragment that matches the depth).
TEST(RenderGl, TheNearestSurfaceShowsAndAtEqualDepthTheFirstDrawn) {
  const glm::vec3 red(100.0f, 0.0f, 0.0f);
  const glm::vec3 green(0.0f, 100.0f, 0.0f);
  const ImageRgbF nearFirst = renderSheets({{0.5f, red, false}, {0.0f, green, false}}, 3.0f);
  const ImageRgbF nearLast = renderSheets({{0.0f, green, false}, {0.5f, red, false}}, 3.0f);
  EXPECT_GT(pixelsShowing(nearFirst, 0), 1000);
  EXPECT_EQ(pixelsShowing(nearFirst, 1), 0);
  EXPECT_TRUE(nearFirst.pixels == nearLast.pixels);
  const ImageRgbF redFirst = renderSheets({{0.0f, red, false}, {0.0f, green, false}}, 3.0f);
  const ImageRgbF greenFirst = renderSheets({{0.0f, green, false}, {0.0f, red, false}}, 3.0f);
  EXPECT_GT(pixelsShowing(redFirst, 0), 1000);
  EXPECT_EQ(pixelsShowing(redFirst, 1), 0);
  EXPECT_EQ(pixelsShowing(greenFirst, 1), pixelsShowing(redFirst, 0));
  EXPECT_EQ(pixelsShowing(greenFirst, 0), 0);
  // Also when the two are drawn with different programs (a glint material, then one without a
  // glint layer, which every BRDF draws with the Cook-Torrance program): the first still wins.
  for (const SpecularModel brdf : allSpecularModels()) {
    SCOPED_TRACE(toString(brdf));
    const ImageRgbF mixed = renderSheets({{0.0f, red, false}, {0.0f, green, false}}, 3.0f,
                                         [](scene::Scene& scene) { scene.materials[0].glint.enabled = true; }, brdf);
    EXPECT_GT(pixelsShowing(mixed, 0), 1000);
    EXPECT_EQ(pixelsShowing(mixed, 1), 0);
  }
}

// glTF alphaMode MASK: the near (red) sheet's texture has alpha 0 on the half of the sheet below
// y = 0 and 1 above, so masked, the far (green) sheet shows through the lower half; opaque (the
// default) or BLEND (drawn opaque), the red covers both halves. A base colour alpha of 0.4 under
// the cutoff 0.5 cuts out the whole sheet, with or without a texture.
TEST(RenderGl, AlphaMaskCutsOutWhereAlphaIsBelowTheCutoff) {
  const glm::vec3 red(100.0f, 0.0f, 0.0f);
  const glm::vec3 green(0.0f, 100.0f, 0.0f);
  auto render = [&](scene::Material::AlphaMode mode, float alpha, bool textured) {
    return renderSheets({{0.5f, red, false}, {0.0f, green, false}}, 3.0f, [&](scene::Scene& scene) {
      scene::Material& near = scene.materials[0];
      near.alphaMode = mode;
      near.baseColour.a = alpha;
      if (!textured) return;
      // u runs along +y on the sheets (makeQuad's halfU): u < 0.5, below y = 0, is cut out.
      scene.textures.push_back({"mask", 4, 1, {255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 255}, true});
      near.baseColourTexture = static_cast<int>(scene.textures.size()) - 1;
    });
  };
  const ImageRgbF opaque = render(scene::Material::AlphaMode::Opaque, 1.0f, true);
  const int sheet = pixelsShowing(opaque, 0);
  EXPECT_GT(sheet, 1000);
  EXPECT_EQ(pixelsShowing(opaque, 1), 0);
  EXPECT_TRUE(render(scene::Material::AlphaMode::Blend, 1.0f, true).pixels == opaque.pixels);

  const ImageRgbF masked = render(scene::Material::AlphaMode::Mask, 1.0f, true);
  EXPECT_NEAR(pixelsShowing(masked, 0), sheet / 2, sheet / 20);
  EXPECT_GT(pixelsShowing(masked, 1), sheet / 4);  // the far sheet, smaller in perspective
  // Which half: the masked image's red rows are the opaque image's upper rows.
  int redAboveMiddle = 0;
  for (int y = 0; y < masked.height; ++y) {
    for (int x = 0; x < masked.width; ++x) {
      const bool upper = y < masked.height / 2;  // rows from the top
      if (masked.pixels[static_cast<std::size_t>(y * masked.width + x)].r > 50.0f && upper) ++redAboveMiddle;
    }
  }
  EXPECT_EQ(redAboveMiddle, pixelsShowing(masked, 0));

  for (const bool textured : {false, true}) {
    const ImageRgbF cut = render(scene::Material::AlphaMode::Mask, 0.4f, textured);
    EXPECT_EQ(pixelsShowing(cut, 0), 0) << textured;
    EXPECT_GT(pixelsShowing(cut, 1), 1000) << textured;
  }
  // The vertex colour's alpha (COLOR_0) takes part too: 0.4 at every vertex cuts the sheet.
  const ImageRgbF byVertices = renderSheets({{0.5f, red, false}, {0.0f, green, false}}, 3.0f, [&](scene::Scene& scene) {
    scene.materials[0].alphaMode = scene::Material::AlphaMode::Mask;
    for (scene::Vertex& v : scene.meshes[0].vertices) v.colour.a = 0.4f;
  });
  EXPECT_EQ(pixelsShowing(byVertices, 0), 0);
  EXPECT_GT(pixelsShowing(byVertices, 1), 1000);
}

// KHR_texture_transform in the rasteriser: an emissive sheet whose texture is red for u < 0.5 and
// green above (u runs along +y on the sheet, makeQuad's halfU) glows red in its lower half; with
// the texture's uv offset by (0.5, 0), the same sheet glows red in its upper half.
TEST(RenderGl, TexturesBeyondTheSizeLimitAreDrawnDownscaledNotBlack) {
  // An emissive texture wider than GL_MAX_TEXTURE_SIZE (16384 on llvmpipe): left half red, right
  // half green. It was drawn black; it must be drawn downscaled, with a warning, the halves in
  // place.
  GLint limit = 0;
  useGlContext();
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &limit);
  const int width = limit + 4000;
  std::vector<std::string> warnings;
  const ImageRgbF image = renderSheets({{0.0f, glm::vec3(100.0f), false}}, 3.0f, [&](scene::Scene& scene) {
    scene::Texture wide{"wide", width, 2, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * 2 * 4, 0), true, {}};
    for (int y = 0; y < 2; ++y) {
      for (int x = 0; x < width; ++x) {
        std::uint8_t* texel = &wide.rgba[4 * (static_cast<std::size_t>(y) * width + x)];
        texel[x < width / 2 ? 0 : 1] = 255;
        texel[3] = 255;
      }
    }
    scene.textures.push_back(std::move(wide));
    scene.materials[0].emissiveTexture = static_cast<int>(scene.textures.size()) - 1;
  }, SpecularModel::Glint, &warnings);
  int red = 0, green = 0;
  for (const glm::vec3& p : image.pixels) {
    red += p.r > 50.0f && p.g < 5.0f;
    green += p.g > 50.0f && p.r < 5.0f;
  }
  EXPECT_GT(red, 300);
  EXPECT_GT(green, 300);
  // And one more: the textured emitter glows but is no area light (scene::findAreaLights).
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("texture 'wide' (" + std::to_string(width) + "x2) exceeds this OpenGL's limit"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find("has an emissive texture: it glows but lights nothing in the rasteriser"), std::string::npos)
      << warnings[1];
}

TEST(RenderGl, TextureTransformMovesTheTexture) {
  const glm::vec3 white(100.0f);
  auto render = [&](scene::UvTransform transform) {
    return renderSheets({{0.0f, white, false}}, 3.0f, [&](scene::Scene& scene) {
      // 4 texels across u: red, red, green, green (sRGB 255 and 0: linear 1 and 0).
      scene.textures.push_back({"halves", 4, 1, {255, 0, 0, 255, 255, 0, 0, 255, 0, 255, 0, 255, 0, 255, 0, 255}, true});
      scene.materials[0].emissiveTexture = static_cast<int>(scene.textures.size()) - 1;
      scene.materials[0].emissiveUv = transform;
    });
  };
  auto redRows = [](const ImageRgbF& image, bool upper) {
    int count = 0;
    for (int y = 0; y < image.height; ++y) {
      for (int x = 0; x < image.width; ++x) {
        const glm::vec3& p = image.pixels[static_cast<std::size_t>(y * image.width + x)];
        if (p.r > 50.0f && p.g < 5.0f && (y < image.height / 2) == upper) ++count;  // rows from the top
      }
    }
    return count;
  };
  const ImageRgbF plain = render({});
  EXPECT_GT(redRows(plain, false), 300);
  EXPECT_EQ(redRows(plain, true), 0);
  scene::UvTransform shifted;
  shifted.offset = glm::vec2(0.5f, 0.0f);
  const ImageRgbF moved = render(shifted);
  EXPECT_GT(redRows(moved, true), 300);
  EXPECT_EQ(redRows(moved, false), 0);
}

// glTF COLOR_0 multiplies the base colour: the sphere with the same colour at every vertex, and a
// white base colour, renders as the sphere with that base colour and white vertices, for every
// BRDF (the colour enters the diffuse term and, on metals, Fresnel's F0).
TEST(RenderGl, VertexColourMultipliesTheBaseColour) {
  useGlContext();
  const glm::vec4 colour(0.2f, 0.6f, 0.9f, 1.0f);
  auto render = [&](glm::vec4 vertexColour, glm::vec4 factor, SpecularModel brdf) {
    scene::Scene scene = scene::makeBuiltinScene("sphere");
    for (scene::Material& m : scene.materials) m.baseColour *= factor;
    for (scene::Mesh& mesh : scene.meshes) {
      for (scene::Vertex& v : mesh.vertices) v.colour = vertexColour;
    }
    gl::Renderer renderer(scene, defaultDictionary());
    gl::FrameSettings frame;
    frame.width = 64;
    frame.height = 64;
    frame.brdf = brdf;
    frame.camera = scene.cameras.at("default");
    ImageRgbF image = gl::renderSupersampled(renderer, frame, 1);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
    return image;
  };
  for (const SpecularModel brdf : allSpecularModels()) {
    const glm::vec4 white(1.0f);
    const ImageRgbF byVertices = render(colour, white, brdf);
    const ImageRgbF byFactor = render(white, colour, brdf);
    const ImageRgbF uncoloured = render(white, white, brdf);
    double largest = 0.0;
    double colourEffect = 0.0;  // how far the colour moves a pixel: the check must be able to fail
    for (std::size_t p = 0; p < byFactor.pixels.size(); ++p) {
      for (int c = 0; c < 3; ++c) {
        const double reference = std::max(1e-6, double(byFactor.pixels[p][c]));
        largest = std::max(largest, std::abs(byVertices.pixels[p][c] - byFactor.pixels[p][c]) / reference);
        colourEffect = std::max(colourEffect, std::abs(uncoloured.pixels[p][c] - byFactor.pixels[p][c]) / reference);
      }
    }
    EXPECT_LT(largest, 1e-5) << toString(brdf);
    EXPECT_GT(colourEffect, 0.1) << toString(brdf);
  }
}

// Where no mesh is drawn the rasteriser shows the environment, as the path tracer's camera rays
// that escape do: the grazing plane's sky, pixel by pixel, against the tracer's camera and
// environment lookup. The bound, 1% of the radiance, covers llvmpipe's 8-bit bilinear weights on a
// smooth sky; a wrong mapping (the sky upside down, or at the wrong height) is off by far more.
TEST(RenderGl, BackgroundIsTheEnvironmentTheTracerSees) {
  useGlContext();
  const scene::Scene scene = scene::makeBuiltinScene("grazing-smooth");
  constexpr int kSide = 64;
  gl::Renderer renderer(scene, defaultDictionary());
  gl::FrameSettings frame;
  frame.width = kSide;
  frame.height = kSide;
  frame.brdf = SpecularModel::CookTorrance;
  frame.camera = scene.cameras.at("default");
  const ImageRgbF image = gl::renderSupersampled(renderer, frame, 1);
  const trace::ProjectiveCamera camera(frame.camera, kSide, kSide);
  const trace::EnvironmentLight environment(scene.environment);
  int sky = 0;
  double largest = 0.0;
  for (int y = 0; y < kSide / 4; ++y) {  // the plane fills the lower half of the frame
    for (int x = 0; x < kSide; ++x) {
      const glm::vec3 expected = environment.radiance(camera.direction({x + 0.5f, y + 0.5f}));
      const glm::vec3 got = image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const double relative = std::abs(got[c] - expected[c]) / expected[c];
        largest = std::max(largest, relative);
        EXPECT_LT(relative, 0.01) << "pixel (" << x << ", " << y << ") channel " << c;
      }
      ++sky;
    }
  }
  EXPECT_GT(environment.radiance(camera.direction({0.5f, 0.5f})).b, 0.0f);  // a sky, not black
  std::printf("background: %d sky pixels, largest relative difference to the tracer's sky %.2e\n", sky, largest);
}

// Anti-aliased edges: at 1 spp, the pixels on the scene's silhouettes (against the sky and
// between meshes) against a 64-frame reference (`glint render --spp 64 --msaa 1`). The edge
// pixels are those whose 64 jittered frames see more than one mesh (or a mesh and the sky): the
// scene drawn with mesh k black and emitting (k + 1, (k + 1)^2, 0), no lights, a black sky, whose
// mean over the frames has green minus red squared, the variance of k + 1 over the pixel, above
// 0.04 (between neighbouring indices, coverage between 4% and 96%). The error there is the RMSE
// relative to the reference's mean over them, for Cook-Torrance (the silhouettes alone) and for
// glint, whose edge pixels also hold glints that the reference averages over 64 positions.
// Measured 2026-12-02 on Mesa llvmpipe (4 samples), 1 sample against 4: sphere 0.652 against 0.257
// (2.54x) for both BRDFs; showroom Cook-Torrance 0.493 against 0.207 (2.38x), glint 0.483 against
// 0.210 (2.30x). Shaded at the pixel's centre instead of the covered samples' centroid, the
// ratios were 1.90x and 1.82x: beyond a silhouette the normal turns away from the camera. What
// is left is the shading's own variation over an edge pixel (grazing Fresnel, the sky's
// reflection), which the reference averages and one shading a surface cannot. Bound: the 2x asked.
// The scenes' clear coats are taken off: a smooth coat turns a silhouette into a mirror of the
// environment (its Fresnel tends to 1 at grazing views), which is shading that varies within the
// pixel, not coverage; with the showroom car's coat, measured 2026-12-07, 0.806 against 0.644
// (1.25x), where the same scene without it gives the ratios above.
TEST(RenderGl, MultisampledEdgesHalveTheSilhouetteError) {
  useGlContext();
  constexpr int kSide = 128;
  constexpr int kReferenceFrames = 64;
  for (const char* name : {"sphere", "showroom"}) {
    scene::Scene scene = scene::makeBuiltinScene(name);
    for (scene::Material& m : scene.materials) m.clearcoat = {};
    scene::Scene indexScene = scene;
    indexScene.materials.clear();
    for (std::size_t k = 0; k < indexScene.meshes.size(); ++k) {
      scene::Material index;
      index.baseColour = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
      const float value = static_cast<float>(k + 1);
      index.emissive = glm::vec3(value, value * value, 0.0f);
      index.doubleSided = scene.materials[static_cast<std::size_t>(scene.meshes[k].material)].doubleSided;
      indexScene.materials.push_back(index);
      indexScene.meshes[k].material = static_cast<int>(k);
    }
    indexScene.lights.clear();
    indexScene.environment = scene::Environment{};
    gl::FrameSettings frame;
    frame.width = kSide;
    frame.height = kSide;
    frame.camera = scene.cameras.at("default");
    frame.msaa = 1;
    gl::Renderer indexRenderer(indexScene, defaultDictionary());
    const ImageRgbF index = gl::renderSupersampled(indexRenderer, frame, kReferenceFrames);
    gl::Renderer renderer(scene, defaultDictionary());
    const int most = renderer.maxMsaaSamples();
    ASSERT_GE(most, 4) << "this OpenGL multisamples at fewer than 4 samples a pixel";
    for (const SpecularModel brdf : {SpecularModel::CookTorrance, SpecularModel::Glint}) {
      frame.brdf = brdf;
      frame.msaa = 1;
      const ImageRgbF reference = gl::renderSupersampled(renderer, frame, kReferenceFrames);
      auto edgeError = [&](int msaa) {
        frame.msaa = msaa;
        const ImageRgbF image = gl::renderSupersampled(renderer, frame, 1);
        EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
        double squared = 0.0, mean = 0.0;
        int count = 0;
        for (std::size_t p = 0; p < image.pixels.size(); ++p) {
          const glm::vec3 i = index.pixels[p];
          if (!(i.g - i.r * i.r > 0.04f)) continue;
          for (int c = 0; c < 3; ++c) {
            const double d = image.pixels[p][c] - reference.pixels[p][c];
            squared += d * d;
            mean += reference.pixels[p][c];
          }
          ++count;
        }
        EXPECT_GT(count, 100) << name;
        return std::sqrt(squared / (3.0 * count)) / (mean / (3.0 * count));
      };
      const double one = edgeError(1);
      const double many = edgeError(most);
      std::printf("%s, %s: edge pixels' relative RMSE against %d frames %.3f at 1 sample, %.3f at %d (%.2fx)\n", name,
                  toString(brdf), kReferenceFrames, one, many, most, one / many);
      EXPECT_GT(one, 2.0 * many) << name << ", " << toString(brdf);
    }
  }
}

// The viewer edits the renderer's materials between frames (Renderer::materials()): the next frame
// draws the edit (the glint material buffer is written again), bit for bit the frame of a renderer
// made with the edited scene.
TEST(RenderGl, EditedMaterialsAreDrawnInTheNextFrame) {
  useGlContext();
  const scene::Scene scene = scene::makeBuiltinScene("sphere");
  scene::Scene edited = scene;
  int layers = 0;
  for (scene::Material& m : edited.materials) {
    if (!m.glint.enabled) continue;
    m.glint.patternSeed += 1;
    m.glint.logDensity -= 4.0f;
    ++layers;
  }
  ASSERT_GT(layers, 0);
  gl::FrameSettings frame;
  frame.width = 96;
  frame.height = 96;
  frame.camera = scene.cameras.at("default");
  gl::Renderer renderer(scene, defaultDictionary());
  renderer.renderFrame(frame);
  const std::vector<float> before = renderer.readRadiance();
  renderer.materials() = edited.materials;
  renderer.renderFrame(frame);
  const std::vector<float> after = renderer.readRadiance();
  gl::Renderer fresh(edited, defaultDictionary());
  fresh.renderFrame(frame);
  EXPECT_NE(after, before);
  EXPECT_EQ(after, fresh.readRadiance());
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(RenderGl, FramesAreIdenticalAcrossRuns) {
  const scene::Scene scene = scene::makeBuiltinScene("sphere");
  const ImageRgbF a = render(scene, SpecularModel::Glint);
  const ImageRgbF b = render(scene, SpecularModel::Glint);
  EXPECT_TRUE(a.pixels == b.pixels);
}

// The fraction of pixels at least twice as bright (luminance) as the same view with Cook-Torrance:
// glints over the smooth lobe's highlight.
double glintPixelFraction(const ImageRgbF& glint, const ImageRgbF& smooth) {
  std::size_t bright = 0;
  for (std::size_t p = 0; p < glint.pixels.size(); ++p) {
    bright += scene::luminance(glint.pixels[p]) > 2.0f * scene::luminance(smooth.pixels[p]);
  }
  return static_cast<double>(bright) / static_cast<double>(glint.pixels.size());
}

TEST(RenderGl, PaperScaleScenesRenderFiniteAndGlint) {
  // The atrium and the car (their goldens would be slow; EveryBrdfRendersEveryBenchmarkSceneWithoutGlErrors
  // draws them with every model), anti-aliased as `glint bench` draws them, 256 x 144: finite,
  // non-negative radiance, and glints: a share of the
  // pixels at least twice the Cook-Torrance render's luminance, a third of what was measured (on
  // llvmpipe, 2026-12-03: the atrium 0.00187 from its `curtain` camera, where curtains and floor
  // glitter in the lamps' light; the car 0.00450 from its default camera). With the glint layers
  // smooth (log density 40, every cell holding microfacets) the share falls below a fifth of that.
  struct Case {
    const char* scene;
    const char* camera;  // where the glint share is measured
    double leastShare;
  };
  useGlContext();
  for (const Case& c : {Case{"atrium", "curtain", 0.0006}, Case{"car", "default", 0.0016}}) {
    SCOPED_TRACE(c.scene);
    const scene::Scene scene = scene::makeBuiltinScene(c.scene);
    const scene::Scene smoothScene = withLogDensity(scene, 40.0f);
    auto draw = [&](gl::Renderer& renderer, SpecularModel brdf) {
      gl::FrameSettings frame;
      frame.width = 256;
      frame.height = 144;
      frame.camera = scene.cameras.at(c.camera);
      frame.brdf = brdf;
      renderer.renderFrame(frame);
      EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
      const std::vector<float> rgba = renderer.readRadiance();
      ImageRgbF image{frame.width, frame.height, {}};
      for (std::size_t p = 0; p + 3 < rgba.size(); p += 4) image.pixels.emplace_back(rgba[p], rgba[p + 1], rgba[p + 2]);
      EXPECT_TRUE(std::all_of(image.pixels.begin(), image.pixels.end(), [](const glm::vec3& p) {
        return std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b) && glm::all(glm::greaterThanEqual(p, glm::vec3(0.0f)));
      })) << toString(brdf);
      return image;
    };
    gl::Renderer renderer(scene, defaultDictionary());
    gl::Renderer smoothRenderer(smoothScene, defaultDictionary());
    const ImageRgbF smooth = draw(renderer, SpecularModel::CookTorrance);
    const double share = glintPixelFraction(draw(renderer, SpecularModel::Glint), smooth);
    const double smoothShare = glintPixelFraction(draw(smoothRenderer, SpecularModel::Glint), smooth);
    std::printf("%s, camera %s: %.5f of the pixels twice Cook-Torrance's luminance; %.5f at log density 40\n", c.scene,
                c.camera, share, smoothShare);
    EXPECT_GT(share, c.leastShare);
    EXPECT_LT(smoothShare, 0.2 * c.leastShare) << "the measure could not tell glints from a smooth lobe";
  }
}

// Golden images: each built-in scene but the two at the paper's scale (tested below) at 256x256, one sample per pixel, as `glint render` writes
// it (tone-mapped, dithered sRGB PNG). On the Mesa that made them the output is byte-identical
// (llvmpipe is deterministic across runs and thread counts, the dither a function of the pixel),
// so the tolerance only absorbs another llvmpipe build's last-bit arithmetic: an RMSE of 0.003 in linear values, while a different glint pattern
// (pattern_seed 1) moves it by more than 0.01 on every scene (checked below, so the bound can fail).
// Set GLINT_UPDATE_GOLDEN=1 to rewrite them (tests/golden/README.md): the test then only writes
// them, says so, and checks nothing.
TEST(RenderGl, BuiltinScenesMatchGoldenImages) {
  const bool update = std::getenv("GLINT_UPDATE_GOLDEN") != nullptr;
  for (const std::string& name : smallBuiltinSceneNames()) {
    const scene::Scene scene = scene::makeBuiltinScene(name);
    const ImageRgbF radiance = render(scene, SpecularModel::Glint);
    const auto rendered = temporaryFolder("golden") / (name + ".png");
    writePng(rendered, displayEncode(radiance, scene.exposure));
    if (update) {
      std::filesystem::copy_file(rendered, goldenPath(name), std::filesystem::copy_options::overwrite_existing);
      std::printf("GLINT_UPDATE_GOLDEN: wrote %s, compared nothing\n", goldenPath(name).string().c_str());
      continue;
    }
    const ImageRgbF golden = readImage(goldenPath(name));
    const ImageError error = compareImages(readImage(rendered), golden);
    EXPECT_LT(error.rmse, 0.003) << name << " differs from " << goldenPath(name) << " (" << rendered << ")";

    scene::Scene otherPattern = scene;
    for (scene::Material& m : otherPattern.materials) m.glint.patternSeed += 1;
    const auto other = temporaryFolder("golden_other") / (name + ".png");
    writePng(other, displayEncode(render(otherPattern, SpecularModel::Glint), scene.exposure));
    EXPECT_GT(compareImages(readImage(other), golden).rmse, 0.01) << name << ": the golden check could not tell patterns apart";
  }
  if (update) GTEST_SKIP() << "GLINT_UPDATE_GOLDEN: the golden images were written, nothing was compared";
}

}  // namespace
}  // namespace glint
