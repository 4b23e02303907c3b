// The path tracer (`glint trace`, docs/trace.md): camera rays and ray differentials against the
// rasteriser's projection, environment sampling, direct light against quadrature, determinism
// across thread counts, the cross-renderer check against the real-time renderer, and the command.
#include <cmath>
#include <cstring>
#include <fstream>
#include <cstdio>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "gl/environment.h"
#include "gl/renderer.h"
#include "gl_support.h"
#include "glint/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/geometry.h"
#include "scene/gltf_writer.h"
#include "test_support.h"
#include "trace/path_tracer.h"
#include "trace/sampling.h"

namespace glint {
namespace {

using namespace glint::test;

// uv = kUvMatrix (x, z) + kUvOffset on the test floor: rotated by 30 degrees and scaled, so that
// neither uv axis follows a world or screen axis.
const glm::mat2 kUvMatrix = 0.4f * glm::mat2(std::cos(0.5236f), std::sin(0.5236f), -std::sin(0.5236f), std::cos(0.5236f));
const glm::vec2 kUvOffset(0.3f, -0.2f);
glm::vec2 floorUv(glm::vec3 p) { return kUvMatrix * glm::vec2(p.x, p.z) + kUvOffset; }

// A 4 x 4 m floor at y = 0 (the only geometry: every upward ray escapes), one material, no lights,
// a black environment, seen obliquely by the default camera.
scene::Scene floorScene() {
  scene::Scene s;
  s.name = "floor";
  scene::Mesh mesh;
  mesh.name = "floor";
  for (glm::vec3 p : {glm::vec3(-2, 0, 2), glm::vec3(2, 0, 2), glm::vec3(2, 0, -2), glm::vec3(-2, 0, -2)}) {
    mesh.vertices.push_back({p, glm::vec3(0, 1, 0), glm::vec4(0.0f), floorUv(p)});
  }
  mesh.indices = {0, 1, 2, 0, 2, 3};
  scene::generateTangents(mesh);
  s.meshes.push_back(mesh);
  scene::Material material;
  material.name = "floor";
  material.baseColour = glm::vec4(0.5f, 0.4f, 0.3f, 1.0f);
  material.roughness = std::sqrt(0.3f);
  s.materials.push_back(material);
  scene::Camera camera;
  camera.position = {0.4f, 1.1f, 2.6f};
  camera.target = {0.0f, 0.0f, -0.3f};
  s.cameras["default"] = camera;
  return s;
}

// A 64 x 32 sky: a gradient from a blue zenith to a grey ground and a small bright sun, so that
// importance sampling has something to find.
scene::Environment skyEnvironment() {
  scene::Environment e;
  e.width = 64;
  e.height = 32;
  for (int y = 0; y < e.height; ++y) {
    for (int x = 0; x < e.width; ++x) {
      const float v = (static_cast<float>(y) + 0.5f) / static_cast<float>(e.height);
      glm::vec3 c = v < 0.5f ? glm::mix(glm::vec3(0.2f, 0.35f, 0.8f), glm::vec3(0.9f), 2.0f * v) : glm::vec3(0.15f);
      if (x >= 40 && x < 43 && y >= 8 && y < 10) c = glm::vec3(60.0f, 55.0f, 45.0f);
      e.pixels.push_back(c);
    }
  }
  e.intensity = 1.0f;
  return e;
}

// glm::project's convention: window coordinates, y up, of a world point.
glm::dvec2 windowPoint(const glm::dmat4& viewProjection, glm::vec3 p, int width, int height) {
  const glm::dvec4 clip = viewProjection * glm::dvec4(glm::dvec3(p), 1.0);
  return {(clip.x / clip.w + 1.0) * 0.5 * width, (clip.y / clip.w + 1.0) * 0.5 * height};
}

// The same pose with a parallel projection that frames the target as the perspective does.
scene::Camera orthographicTwin(scene::Camera camera) {
  camera.projection = scene::Camera::Projection::Orthographic;
  camera.orthographicHalfHeight =
      glm::length(camera.target - camera.position) * std::tan(glm::radians(0.5f * camera.verticalFovDegrees));
  return camera;
}

const char* projectionName(const scene::Camera& camera) {
  return camera.projection == scene::Camera::Projection::Orthographic ? "orthographic" : "perspective";
}

// ---- camera rays and ray differentials ---------------------------------------------------------

TEST(Trace, CameraRaysPierceTheRasterisersPixels) {
  scene::Camera perspective;
  perspective.position = {1.3f, 0.7f, 2.9f};
  perspective.target = {-0.2f, 0.1f, 0.0f};
  perspective.up = {0.1f, 1.0f, 0.05f};
  perspective.verticalFovDegrees = 37.0f;
  const int width = 96;
  const int height = 64;
  for (const scene::Camera& camera : {perspective, orthographicTwin(perspective)}) {
    const trace::ProjectiveCamera projective(camera, width, height);
    const glm::dmat4 viewProjection(gl::viewProjection(camera, width, height, glm::vec2(0.0f), glm::vec3(-1.0f),
                                                       glm::vec3(1.0f)));
    Pcg32 rng(7, 1);
    for (int k = 0; k < 200; ++k) {
      const glm::vec2 film(uniform(rng, 0.0f, width), uniform(rng, 0.0f, height));
      const trace::RayDifferential rays = projective.generateRay(film);
      const std::pair<const trace::Ray*, glm::vec2> cases[] = {
          {&rays.ray, film}, {&rays.rx, film + glm::vec2(1, 0)}, {&rays.ry, film + glm::vec2(0, 1)}};
      for (const auto& [ray, expected] : cases) {
        for (float t : {0.7f, 3.5f}) {
          const glm::dvec2 window = windowPoint(viewProjection, ray->origin + t * ray->direction, width, height);
          // Image rows go down, window y up.
          EXPECT_NEAR(window.x, expected.x, 1e-3) << projectionName(camera) << " " << k;
          EXPECT_NEAR(height - window.y, expected.y, 1e-3) << projectionName(camera) << " " << k;
        }
      }
    }
  }
}

TEST(Trace, CameraRaysHitWhatTheRasteriserDrawsAtThePixelCentre) {
  const scene::Scene scene = scene::makeBuiltinScene("sphere");
  const scene::Camera& perspective = scene.cameras.at("default");
  const int size = 64;
  const trace::SceneGeometry geometry(scene);
  for (const scene::Camera& camera : {perspective, orthographicTwin(perspective)}) {
    const trace::ProjectiveCamera projective(camera, size, size);
    const glm::dmat4 viewProjection(
        gl::viewProjection(camera, size, size, glm::vec2(0.0f), scene.boundsMin(), scene.boundsMax()));
    int hits = 0;
    for (int y = 0; y < size; y += 3) {
      for (int x = 0; x < size; x += 3) {
        const glm::vec2 centre(x + 0.5f, y + 0.5f);
        const trace::Ray ray = projective.generateRay(centre).ray;
        const auto hit = geometry.intersect(ray);
        if (!hit) continue;
        ++hits;
        const glm::vec3 p = trace::surfacePoint(scene, *hit).position;
        const glm::dvec2 window = windowPoint(viewProjection, p, size, size);
        EXPECT_NEAR(window.x, centre.x, 2e-3) << projectionName(camera) << " " << x << "," << y;
        EXPECT_NEAR(size - window.y, centre.y, 2e-3) << projectionName(camera) << " " << x << "," << y;
      }
    }
    EXPECT_GT(hits, 100) << projectionName(camera);
  }
}

// glTF alphaMode MASK in the tracer: rays pass through the near sheet where its base colour's alpha
// is below the cutoff, both to find the nearest hit and to test for shadows. The near sheet's
// texture has alpha 0 for u < 0.5 (below y = 0: makeQuad's u runs along halfU = +y) and 1 above,
// as in RenderGl.AlphaMaskCutsOutWhereAlphaIsBelowTheCutoff.
TEST(Trace, AlphaMaskLetsRaysThroughWhereAlphaIsBelowTheCutoff) {
  auto sheets = [](scene::Material::AlphaMode mode, float alpha, bool textured) {
    scene::Scene scene;
    scene.materials.resize(2);
    scene.materials[0].alphaMode = mode;
    scene.materials[0].baseColour.a = alpha;
    if (textured) {
      scene.textures.push_back({"mask", 4, 1, {255, 255, 255, 0, 255, 255, 255, 0, 255, 255, 255, 255, 255, 255, 255, 255}, true});
      scene.materials[0].baseColourTexture = 0;
    }
    scene.meshes.push_back(scene::makeQuad("near", 0, glm::vec3(0.0f), {0, 1, 0}, {1, 0, 0}));
    scene.meshes.push_back(scene::makeQuad("far", 1, glm::vec3(0.0f, 0.0f, -0.5f), {0, 1, 0}, {1, 0, 0}));
    return scene;
  };
  const trace::Ray below{glm::vec3(0.0f, -0.5f, 3.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
  const trace::Ray above{glm::vec3(0.0f, 0.5f, 3.0f), glm::vec3(0.0f, 0.0f, -1.0f)};
  auto meshHit = [](const trace::SceneGeometry& geometry, const trace::Ray& ray) {
    const auto hit = geometry.intersect(ray);
    return hit ? static_cast<int>(hit->mesh) : -1;
  };
  const trace::SceneGeometry opaque(sheets(scene::Material::AlphaMode::Opaque, 1.0f, true));
  EXPECT_EQ(meshHit(opaque, below), 0);
  EXPECT_EQ(meshHit(opaque, above), 0);
  EXPECT_TRUE(opaque.occluded(below, 3.2f));

  const trace::SceneGeometry masked(sheets(scene::Material::AlphaMode::Mask, 1.0f, true));
  EXPECT_EQ(meshHit(masked, below), 1);
  EXPECT_NEAR(masked.intersect(below)->t, 3.5f, 1e-5f);
  EXPECT_EQ(meshHit(masked, above), 0);
  EXPECT_FALSE(masked.occluded(below, 3.2f));  // up to a point between the sheets
  EXPECT_TRUE(masked.occluded(above, 3.2f));

  for (const bool textured : {false, true}) {
    const trace::SceneGeometry cut(sheets(scene::Material::AlphaMode::Mask, 0.4f, textured));
    EXPECT_EQ(meshHit(cut, above), 1) << textured;
    EXPECT_FALSE(cut.occluded(above, 3.2f)) << textured;
  }
  // The vertex colour's alpha (COLOR_0) takes part too, interpolated: 0 at the sheet's lower
  // corners (y = -1) and 1 at its upper ones gives alpha 0.25 at y = -0.5 and 0.75 at y = 0.5.
  scene::Scene graded = sheets(scene::Material::AlphaMode::Mask, 1.0f, false);
  for (scene::Vertex& v : graded.meshes[0].vertices) v.colour.a = v.position.y > 0.0f ? 1.0f : 0.0f;
  const trace::SceneGeometry byVertices(graded);
  EXPECT_EQ(meshHit(byVertices, below), 1);
  EXPECT_EQ(meshHit(byVertices, above), 0);
}

// KHR_texture_transform in the tracer moves the footprint with the uv: a 4 x 4 black-and-white
// checker seen through a scale of 16, with a footprint of a quarter texel, must be looked up as the
// untransformed texture at the same transformed uv with a footprint 16 times larger (the whole
// texture: its coarsest, grey mip level), not as the black texel alone.
TEST(Trace, TextureTransformScalesTheFootprint) {
  scene::Scene scene;
  scene.materials.resize(1);
  scene.materials[0].metallic = 0.0f;
  std::vector<std::uint8_t> checker;
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {
      const std::uint8_t v = (i + j) % 2 == 0 ? 0 : 255;
      checker.insert(checker.end(), {v, v, v, 255});
    }
  }
  scene.textures.push_back({"checker", 4, 4, checker, false});
  scene.materials[0].baseColourTexture = 0;
  auto albedo = [&](const scene::UvTransform& transform, glm::vec2 uv, float footprint) {
    scene.materials[0].baseColourUv = transform;
    const trace::SceneMaterials materials(scene, defaultDictionary(), SpecularModel::CookTorrance);
    trace::SurfacePoint point;
    point.uv = uv;
    const trace::UvDerivatives derivatives{glm::vec2(footprint, 0.0f), glm::vec2(0.0f, footprint)};
    return materials.shade(point, derivatives, glm::vec3(0.0f, 0.0f, 1.0f)).material.diffuse().r * 3.14159265f;
  };
  const glm::vec2 blackTexel(0.125f);  // texel (0, 0)'s centre
  EXPECT_LT(albedo({}, blackTexel, 1.0f / 16.0f), 1e-6f);
  const float whole = albedo({}, blackTexel, 1.0f);
  EXPECT_GT(whole, 0.2f);
  scene::UvTransform sixteen;
  sixteen.scale = glm::vec2(16.0f);
  sixteen.offset = blackTexel;
  EXPECT_EQ(albedo(sixteen, glm::vec2(0.0f), 1.0f / 16.0f), whole);
}

// On a plane, uv is a projective function of the window position, so the differences a 2 x 2 quad
// takes between neighbouring pixel centres (what dFdx / dFdy return) are exact values, not
// approximations of a derivative. They are computed here from gl::viewProjection alone (unproject,
// intersect the plane, evaluate the uv map) and must equal the ray differentials' duv/dx, duv/dy.
// Sign: duv/dy is towards the next image row (down); dFdy is towards window y (up), its negative.
TEST(Trace, RayDifferentialsGiveTheRasterisersScreenDerivativesOnAPlane) {
  const scene::Scene scene = floorScene();
  const scene::Camera& perspective = scene.cameras.at("default");
  const int width = 160;
  const int height = 120;
  const trace::SceneGeometry geometry(scene);
  for (const scene::Camera& camera : {perspective, orthographicTwin(perspective)}) {
    const trace::ProjectiveCamera projective(camera, width, height);
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(
        gl::viewProjection(camera, width, height, glm::vec2(0.0f), scene.boundsMin(), scene.boundsMax())));
    auto uvAtWindow = [&](double wx, double wy) {
      const glm::dvec2 ndc(2.0 * wx / width - 1.0, 2.0 * wy / height - 1.0);
      glm::dvec4 nearPoint = inverse * glm::dvec4(ndc, -1.0, 1.0);
      glm::dvec4 farPoint = inverse * glm::dvec4(ndc, 1.0, 1.0);
      const glm::dvec3 a = glm::dvec3(nearPoint) / nearPoint.w;
      const glm::dvec3 b = glm::dvec3(farPoint) / farPoint.w;
      const glm::dvec3 p = a + (b - a) * (a.y / (a.y - b.y));  // the plane y = 0
      return glm::dvec2(glm::dmat2(kUvMatrix) * glm::dvec2(p.x, p.z) + glm::dvec2(kUvOffset));
    };
    int checked = 0;
    double largest = 0.0;
    for (int y = 0; y < height; y += 7) {
      for (int x = 0; x < width; x += 7) {
        const trace::RayDifferential rays = projective.generateRay(glm::vec2(x + 0.5f, y + 0.5f));
        const auto hit = geometry.intersect(rays.ray);
        if (!hit) continue;
        const trace::SurfacePoint point = trace::surfacePoint(scene, *hit);
        const trace::UvDerivatives d = trace::uvDerivatives(point, rays);
        const double wx = x + 0.5;
        const double wy = height - (y + 0.5);
        const glm::dvec2 uv = uvAtWindow(wx, wy);
        const glm::dvec2 dFdx = uvAtWindow(wx + 1.0, wy) - uv;
        const glm::dvec2 nextRow = uvAtWindow(wx, wy - 1.0) - uv;
        const double scale = std::max(glm::length(dFdx), glm::length(nextRow));
        EXPECT_NEAR(point.uv.x, uv.x, 1e-5) << projectionName(camera) << " " << x << "," << y;
        EXPECT_NEAR(point.uv.y, uv.y, 1e-5) << projectionName(camera) << " " << x << "," << y;
        const double difference =
            std::max(glm::length(glm::dvec2(d.duvdx) - dFdx), glm::length(glm::dvec2(d.duvdy) - nextRow)) / scale;
        // The same quantity by two computations: float rounding only (measured 2.8e-5).
        EXPECT_LT(difference, 2e-4) << projectionName(camera) << " " << x << "," << y;
        largest = std::max(largest, difference);
        ++checked;
      }
    }
    EXPECT_GT(checked, 200) << projectionName(camera);
    std::printf("[ measured ] %s: %d pixels, largest difference %.2g of the footprint\n", projectionName(camera),
                checked, largest);
  }
}

// Later path vertices get approximateRays' footprint: for a parallel projection it is a pixel's
// width wherever the point lies, so at every point the camera sees it equals the footprint of the
// camera ray through that point's pixel; from a pinhole it is a pixel's angle at the image centre,
// so it equals the camera ray's footprint there.
TEST(Trace, ApproximateRaysGiveACameraPixelsFootprint) {
  const scene::Scene scene = floorScene();
  const scene::Camera& perspective = scene.cameras.at("default");
  const int width = 160;
  const int height = 120;
  const trace::SceneGeometry geometry(scene);
  auto compare = [&](const trace::ProjectiveCamera& camera, glm::vec2 film) {
    const trace::RayDifferential rays = camera.generateRay(film);
    const auto hit = geometry.intersect(rays.ray);
    if (!hit) return -1.0;
    const trace::SurfacePoint point = trace::surfacePoint(scene, *hit);
    const trace::UvDerivatives exact = trace::uvDerivatives(point, rays);
    const trace::UvDerivatives approximate = trace::uvDerivatives(point, camera.approximateRays(point.position));
    const double scale = std::max(glm::length(exact.duvdx), glm::length(exact.duvdy));
    return std::max(glm::length(approximate.duvdx - exact.duvdx), glm::length(approximate.duvdy - exact.duvdy)) /
           scale;
  };
  const trace::ProjectiveCamera parallel(orthographicTwin(perspective), width, height);
  int checked = 0;
  for (int y = 0; y < height; y += 7) {
    for (int x = 0; x < width; x += 7) {
      const double difference = compare(parallel, glm::vec2(x + 0.5f, y + 0.5f));
      if (difference < 0.0) continue;
      EXPECT_LT(difference, 1e-4) << x << "," << y;  // float rounding only
      ++checked;
    }
  }
  EXPECT_GT(checked, 200);
  const double centre = compare(trace::ProjectiveCamera(perspective, width, height), glm::vec2(width, height) * 0.5f);
  EXPECT_GE(centre, 0.0);  // the floor is at the image centre
  EXPECT_LT(centre, 1e-4);
  // Off centre, a pinhole's pixel subtends a smaller angle: approximateRays is then an estimate.
  const double corner = compare(trace::ProjectiveCamera(perspective, width, height), glm::vec2(5.5f, height - 5.5f));
  EXPECT_GT(corner, 1e-3);
}

TEST(Trace, EquirectMappingIsTheRealTimeRenderers) {
  for (int j = 0; j <= 16; ++j) {
    for (int i = 0; i <= 32; ++i) {
      const glm::vec2 uv(i / 32.0f, j / 16.0f);
      const glm::vec3 d = trace::directionFromEquirect(uv);
      const glm::vec3 expected = gl::equirectDirection(uv.x, uv.y);
      EXPECT_LT(glm::length(d - expected), 1e-6f) << i << "," << j;
      if (j > 0 && j < 16 && i > 0 && i < 32) {
        const glm::vec2 back = trace::equirectFromDirection(d);
        EXPECT_NEAR(back.x, uv.x, 1e-5f);
        EXPECT_NEAR(back.y, uv.y, 1e-5f);
      }
    }
  }
}

// ---- environment sampling and the integrator ---------------------------------------------------

// The density of the environment's samples integrates to 1 over the sphere, the pdf a sample
// carries is the one pdf() gives for its direction, and sampling estimates the environment's
// integral (luminance importance sampling: the estimate is nearly exact).
TEST(TraceStat, EnvironmentSamplingIsANormalisedConsistentDensity) {
  const scene::Environment sky = skyEnvironment();
  const trace::EnvironmentLight light(sky);
  const glm::vec3 normal(0, 1, 0);
  // Midpoint quadrature in (u, v): d(omega) = 2 pi^2 sin(theta) du dv.
  const int n = 1024;
  double pdfIntegral = 0.0;
  glm::dvec3 radianceIntegral(0.0);
  for (int j = 0; j < n / 2; ++j) {
    for (int i = 0; i < n; ++i) {
      const glm::vec2 uv((i + 0.5f) / n, (j + 0.5f) / (n / 2));
      const glm::vec3 d = trace::directionFromEquirect(uv);
      const double dOmega = 2.0 * M_PI * M_PI * std::sin(M_PI * uv.y) / (static_cast<double>(n) * (n / 2));
      pdfIntegral += light.pdf(d, normal) * dOmega;
      radianceIntegral += glm::dvec3(light.radiance(d)) * dOmega;
    }
  }
  EXPECT_NEAR(pdfIntegral, 1.0, 2e-3);

  Pcg32 rng(11, 3);
  const int samples = 20000;
  glm::dvec3 estimate(0.0);
  int inconsistent = 0;
  for (int k = 0; k < samples; ++k) {
    const auto s = light.sample(trace::uniformFloat2(rng), normal);
    ASSERT_TRUE(s.has_value());
    if (std::abs(s->pdf - light.pdf(s->direction, normal)) > 1e-3f * s->pdf) ++inconsistent;
    estimate += glm::dvec3(s->radiance) / static_cast<double>(s->pdf);
  }
  estimate /= samples;
  // A sample within float rounding of a cell's edge, or at a pole (where the direction cannot
  // carry its azimuth), may map back to the neighbouring cell: measured 2 of 20,000.
  EXPECT_LE(inconsistent, samples / 1000);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(estimate[c], radianceIntegral[c], 0.01 * radianceIntegral[c]) << c;

  // A uniform environment is sampled cosine-weighted about the normal.
  scene::Environment grey;
  grey.uniform = glm::vec3(0.5f);
  const trace::EnvironmentLight uniformLight(grey);
  for (int k = 0; k < 100; ++k) {
    const auto s = uniformLight.sample(trace::uniformFloat2(rng), normal);
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(s->pdf, glm::dot(s->direction, normal) / trace::kPi, 1e-4f);
    EXPECT_EQ(s->radiance, glm::vec3(0.5f));
  }
}

// Direct light from the environment on the floor (nothing occludes it: max depth 1 is exactly
// the integral of f L cos over the hemisphere) estimated by the integrator -- environment samples
// and BSDF samples combined by the power heuristic -- against a quadrature of the same material's
// f. Checks the MIS weights and both pdfs; the material itself is the cross-renderer check's.
// Glint at log density 40 is smooth enough for the quadrature (at 13 its narrow lobes are not).
TEST(TraceStat, DirectEnvironmentLightMatchesQuadrature) {
  scene::Scene scene = floorScene();
  scene.environment = skyEnvironment();
  const Dictionary& dictionary = defaultDictionary();
  for (const bool glintLayer : {false, true}) {
    scene.materials[0].glint.enabled = glintLayer;
    scene.materials[0].glint.alpha = glm::vec2(0.3f);
    scene.materials[0].glint.logDensity = 40.0f;
    trace::TraceSettings settings;
    settings.width = 48;
    settings.height = 36;
    settings.maxDepth = 1;
    settings.pixelCentres = true;
    settings.camera = scene.cameras.at("default");
    const trace::PathTracer tracer(scene, dictionary, settings);
    for (const glm::ivec2 pixel : {glm::ivec2(24, 30), glm::ivec2(10, 25), glm::ivec2(40, 33)}) {
      const trace::RayDifferential rays =
          tracer.camera().generateRay(glm::vec2(pixel) + glm::vec2(0.5f));
      const auto hit = tracer.geometry().intersect(rays.ray);
      ASSERT_TRUE(hit.has_value());
      const trace::SurfacePoint point = trace::surfacePoint(scene, *hit);
      const trace::ShadedPoint shaded =
          tracer.materials().shade(point, trace::uvDerivatives(point, rays), -rays.ray.direction);
      // Quadrature over the hemisphere in (cos theta, phi) (d omega = d(cos theta) d phi).
      const trace::EnvironmentLight sky(scene.environment);
      const int nTheta = 384;
      const int nPhi = 768;
      glm::dvec3 reference(0.0);
      for (int j = 0; j < nTheta; ++j) {
        const float cosTheta = (j + 0.5f) / nTheta;
        const float sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
        for (int i = 0; i < nPhi; ++i) {
          const float phi = 2.0f * trace::kPi * (i + 0.5f) / nPhi;
          const glm::vec3 wi(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
          const glm::vec3 f = shaded.material.f(shaded.wo, wi);
          reference += glm::dvec3(f * sky.radiance(shaded.frame.toWorld(wi))) * static_cast<double>(cosTheta);
        }
      }
      reference *= 2.0 * M_PI / (static_cast<double>(nTheta) * nPhi);
      const int samples = 4096;
      glm::dvec3 sum(0.0);
      glm::dvec3 sum2(0.0);
      for (int s = 0; s < samples; ++s) {
        const glm::dvec3 v(tracer.samplePixel(pixel.x, pixel.y, s));
        sum += v;
        sum2 += v * v;
      }
      const glm::dvec3 mean = sum / static_cast<double>(samples);
      const glm::dvec3 standardError = glm::sqrt(glm::max(sum2 / static_cast<double>(samples) - mean * mean,
                                                          glm::dvec3(0.0)) /
                                                 static_cast<double>(samples));
      for (int c = 0; c < 3; ++c) {
        // 4 standard errors, plus 1% for the quadrature of a glossy lobe on a 384 x 768 grid.
        EXPECT_NEAR(mean[c], reference[c], 4.0 * standardError[c] + 0.01 * reference[c])
            << (glintLayer ? "glint" : "cook-torrance") << " pixel " << pixel.x << "," << pixel.y << " channel " << c;
      }
    }
  }
}

// ---- emissive triangles as lights ---------------------------------------------------------------

// A rectangle in the plane y = height, x in [x0, x1], z in [z0, z1], u along x and v along z,
// facing down (its counter-clockwise side towards -y) or up.
scene::Mesh horizontalRectangle(const std::string& name, float x0, float x1, float z0, float z1, float height,
                                bool facingDown, int material) {
  scene::Mesh mesh;
  mesh.name = name;
  mesh.material = material;
  const glm::vec3 normal(0.0f, facingDown ? -1.0f : 1.0f, 0.0f);
  for (const glm::vec2 corner : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
    const glm::vec3 p(glm::mix(x0, x1, corner.x), height, glm::mix(z0, z1, corner.y));
    mesh.vertices.push_back({p, normal, glm::vec4(0.0f), corner});
  }
  // (0,0) (1,0) (1,1) turns counter-clockwise seen from -y.
  mesh.indices = facingDown ? std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3} : std::vector<std::uint32_t>{0, 2, 1, 0, 3, 2};
  scene::generateTangents(mesh);
  return mesh;
}

// The configuration factor from a differential area to a parallel rectangle a x b at distance h,
// the rectangle's corner on the area's normal (Howell's catalogue of configuration factors, B-3;
// the sum over four such rectangles covers any point under a rectangle). A Lambertian emitter of
// radiance L gives the area the irradiance E = pi L F.
double cornerRectangleFactor(double a, double b, double h) {
  const double x = a / h;
  const double y = b / h;
  const double sx = std::sqrt(1.0 + x * x);
  const double sy = std::sqrt(1.0 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2.0 * M_PI);
}

// The factor of the rectangle [x0, x1] x [z0, z1] at height h from the floor point (px, 0, pz)
// below it (px in [x0, x1], pz in [z0, z1]): four corner rectangles.
double rectangleFactor(double x0, double x1, double z0, double z1, double h, double px, double pz) {
  double f = 0.0;
  for (const double a : {px - x0, x1 - px}) {
    for (const double b : {pz - z0, z1 - pz}) {
      if (a > 0.0 && b > 0.0) f += cornerRectangleFactor(a, b, h);
    }
  }
  return f;
}

// A 20 x 20 m floor, red diffuse (base colour (0.8, 0, 0), metallic 0), under a square lamp 2 m
// wide at height 1 facing down (emissive factor kLampRadiance in every channel, base colour black),
// and beside it (`withStrip`) a strip facing up, three times as bright, whose back the floor sees:
// glTF's single-sided emission lights nothing below it. No other light, a black environment. The
// camera looks down at the floor past the lamp's edge, from far enough that a pixel's footprint
// on the lamp spans few texels of its texture (EmissiveTexturesLightAtTheSampledPoint).
//
// glTF's metal-roughness material adds a white specular lobe (F0 = 0.04) to every base colour;
// it reflects the same in all channels, so the red channel minus the green one is the Lambertian
// term alone: 0.8 / pi times the irradiance E.
constexpr float kLampRadiance = 4.0f;
constexpr float kFloorRed = 0.8f;

scene::Scene lampScene(float lampHalfSide = 1.0f, bool withStrip = true) {
  scene::Scene s;
  s.name = "lamp";
  scene::Material floor;
  floor.name = "floor";
  floor.baseColour = glm::vec4(kFloorRed, 0.0f, 0.0f, 1.0f);
  floor.roughness = 0.6f;
  scene::Material lamp;
  lamp.name = "lamp";
  lamp.baseColour = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  lamp.emissive = glm::vec3(kLampRadiance);
  scene::Material strip = lamp;
  strip.name = "strip";
  strip.emissive = glm::vec3(3.0f * kLampRadiance);
  s.materials = {floor, lamp, strip};
  s.meshes.push_back(horizontalRectangle("floor", -10, 10, -10, 10, 0.0f, false, 0));
  s.meshes.push_back(horizontalRectangle("lamp", -lampHalfSide, lampHalfSide, -lampHalfSide, lampHalfSide, 1.0f, true, 1));
  if (withStrip) s.meshes.push_back(horizontalRectangle("strip", 1.5f, 2.5f, -1.0f, 1.0f, 0.5f, false, 2));
  scene::Camera camera;
  camera.position = {-7.0f, 4.0f, 0.3f};
  camera.target = {0.0f, 0.0f, 0.0f};
  s.cameras["default"] = camera;
  return s;
}

// One pixel whose centre sees `target` on the floor, direct light only (max depth 1: the
// first hit's light samples and its BSDF sample's hit on an emitter).
trace::TraceSettings lampSettings(const scene::Scene& scene, glm::vec3 target, int size = 1, float fov = 45.0f) {
  trace::TraceSettings settings;
  settings.width = size;
  settings.height = size;
  settings.maxDepth = 1;
  settings.pixelCentres = true;
  settings.camera = scene.cameras.at("default");
  settings.camera.target = target;
  settings.camera.verticalFovDegrees = fov;
  return settings;
}

struct Estimate {
  double mean;
  double variance;  // of one sample
  double standardError() const { return std::sqrt(variance / samples); }
  int samples;
};

// The red minus green channel of `samples` samples of pixel (x, y).
Estimate lambertianTerm(const trace::PathTracer& tracer, glm::ivec2 pixel, int samples) {
  double sum = 0.0;
  double sum2 = 0.0;
  for (int s = 0; s < samples; ++s) {
    const glm::vec3 v = tracer.samplePixel(pixel.x, pixel.y, s);
    const double d = static_cast<double>(v.r) - static_cast<double>(v.g);
    sum += d;
    sum2 += d * d;
  }
  const double mean = sum / samples;
  return {mean, std::max(sum2 / samples - mean * mean, 0.0), samples};
}

TEST(Trace, EmissionIsOneSidedUnlessTheMaterialIsDoubleSided) {
  // The lamp faces down: seen from below it glows, from above only when double-sided. glTF culls
  // a single-sided surface's back, so a ray from above passes through it to the floor, and draws
  // a double-sided one's with the same emission.
  scene::Scene scene = lampScene(1.0f, false);
  for (const bool doubleSided : {false, true}) {
    scene.materials[1].doubleSided = doubleSided;
    trace::TraceSettings settings = lampSettings(scene, glm::vec3(0.0f));
    const trace::PathTracer tracer(scene, defaultDictionary(), settings);
    for (const float side : {-1.0f, 1.0f}) {
      // From 0.5 m below or above the lamp, straight at it (from below past nothing but air).
      const trace::Ray ray{glm::vec3(0.2f, 1.0f + 0.5f * side, 0.1f), glm::vec3(0.0f, -side, 0.0f)};
      const bool front = side < 0.0f;
      const auto hit = tracer.geometry().intersect(ray);
      ASSERT_TRUE(hit.has_value());
      if (!front && !doubleSided) {
        EXPECT_NE(hit->mesh, 1u) << "a single-sided lamp's back stops a radiance ray";
        continue;
      }
      ASSERT_EQ(hit->mesh, 1u) << (doubleSided ? "double-sided" : "single-sided") << (front ? ", front" : ", back");
      const trace::SurfacePoint point = trace::surfacePoint(scene, *hit);
      const glm::vec3 emitted = tracer.materials().emission(point, {}, -ray.direction);
      EXPECT_EQ(emitted, glm::vec3(kLampRadiance))
          << (doubleSided ? "double-sided" : "single-sided") << (front ? ", front" : ", back");
    }
  }
}

TEST(TraceStat, AnEmissiveSquareGivesTheAnalyticIrradiance) {
  const scene::Scene scene = lampScene();
  for (const float px : {0.0f, 0.6f}) {
    const glm::vec3 target(px, 0.0f, 0.0f);
    const trace::PathTracer tracer(scene, defaultDictionary(), lampSettings(scene, target));
    const double irradiance = M_PI * kLampRadiance * rectangleFactor(-1, 1, -1, 1, 1.0, px, 0.0);
    const double expected = kFloorRed / M_PI * irradiance;
    const Estimate estimate = lambertianTerm(tracer, {0, 0}, 65536);
    std::printf("[ lamp     ] floor point x = %.1f: expected %.5f, traced %.5f (standard error %.2g)\n", px, expected,
                estimate.mean, estimate.standardError());
    // 2% of the value, at least 4 standard errors (measured: 0.33% and 0.40%) -- the lamp's
    // light is counted once, through both strategies, and the upward strip's back adds nothing
    // (glowing from both sides, it adds 5% and 22%).
    EXPECT_LT(4.0 * estimate.standardError(), 0.02 * expected);
    EXPECT_NEAR(estimate.mean, expected, 0.02 * expected) << "x = " << px;
  }
}

// Emitter sampling with MIS against the BSDF's samples alone (the same material's sampler, rays
// and emission, counting every emitter hit fully), on the floor under a lamp 2 m and one 0.4 m
// wide (no strip): at equal sample counts the variance is lower, by far for the small lamp
// (measured: 6x and 8,000x lower).
TEST(TraceStat, EmitterSamplingHasLessVarianceThanBsdfSamplingAlone) {
  for (const float halfSide : {1.0f, 0.2f}) {
    const scene::Scene scene = lampScene(halfSide, false);
    const glm::vec3 target(0.1f, 0.0f, 0.05f);
    const trace::PathTracer tracer(scene, defaultDictionary(), lampSettings(scene, target));
    const int samples = 8192;
    const Estimate mis = lambertianTerm(tracer, {0, 0}, samples);

    const trace::RayDifferential rays = tracer.camera().generateRay(glm::vec2(0.5f));
    const auto hit = tracer.geometry().intersect(rays.ray);
    ASSERT_TRUE(hit.has_value());
    const trace::SurfacePoint point = trace::surfacePoint(scene, *hit);
    ASSERT_EQ(point.material, 0);
    const trace::ShadedPoint shaded = tracer.materials().shade(point, trace::uvDerivatives(point, rays), -rays.ray.direction);
    Pcg32 rng(5, 9);
    double sum = 0.0;
    double sum2 = 0.0;
    for (int s = 0; s < samples; ++s) {
      const float uChoice = trace::uniformFloat(rng);
      const auto bounce = shaded.material.sample(shaded.wo, uChoice, trace::uniformFloat2(rng));
      double d = 0.0;
      if (bounce) {
        const trace::Ray ray = trace::spawnRay(point, shaded.frame.toWorld(bounce->wi));
        if (const auto light = tracer.geometry().intersect(ray)) {
          const trace::SurfacePoint lit = trace::surfacePoint(scene, *light);
          const glm::vec3 value = bounce->weight * tracer.materials().emission(lit, {}, -ray.direction);
          d = static_cast<double>(value.r) - static_cast<double>(value.g);
        }
      }
      sum += d;
      sum2 += d * d;
    }
    const double bsdfMean = sum / samples;
    const Estimate bsdf{bsdfMean, std::max(sum2 / samples - bsdfMean * bsdfMean, 0.0), samples};
    std::printf("[ lamp     ] half side %.1f: variance MIS %.3g, BSDF alone %.3g (means %.4f, %.4f)\n", halfSide,
                mis.variance, bsdf.variance, mis.mean, bsdf.mean);
    // Both estimate the same value (within 4 standard errors of their difference) ...
    EXPECT_NEAR(mis.mean, bsdf.mean, 4.0 * std::sqrt(mis.variance / samples + bsdf.variance / samples));
    // ... and MIS with less than half the variance (a third for the small lamp).
    EXPECT_LT(mis.variance, (halfSide < 0.5f ? 1.0 / 3.0 : 0.5) * bsdf.variance) << "half side " << halfSide;
  }
}

// The lamp with an emissive texture, black on its half x < 0 and white on the other (128 x 1
// texels, sRGB): emitter samples read the texture at their own uv, so the floor gets the light of
// the white half alone. The 65 x 65 pixel image at a 10 degree field of view keeps the texture's
// footprint to a few texels at the lamp (its level of detail blurs the edge; measured -0.3% and
// -1.6% off the sharp edge's value).
TEST(TraceStat, EmissiveTexturesLightAtTheSampledPoint) {
  scene::Scene scene = lampScene();
  scene::Texture halves;
  halves.name = "halves";
  halves.width = 128;
  halves.height = 1;
  halves.srgb = true;
  for (int x = 0; x < halves.width; ++x) {
    const std::uint8_t value = x < halves.width / 2 ? 0 : 255;
    halves.rgba.insert(halves.rgba.end(), {value, value, value, 255});
  }
  scene.textures.push_back(halves);
  scene.materials[1].emissiveTexture = 0;
  for (const float px : {0.0f, 0.6f}) {
    const glm::vec3 target(px, 0.0f, 0.0f);
    const trace::PathTracer tracer(scene, defaultDictionary(), lampSettings(scene, target, 65, 10.0f));
    const double expected = kFloorRed * kLampRadiance * rectangleFactor(0, 1, -1, 1, 1.0, px, 0.0);
    const Estimate estimate = lambertianTerm(tracer, {32, 32}, 65536);
    std::printf("[ lamp     ] textured, floor point x = %.1f: expected %.5f, traced %.5f (standard error %.2g)\n", px,
                expected, estimate.mean, estimate.standardError());
    // 2%, as above; the whole lamp would give 2 and 1.6 times as much.
    EXPECT_NEAR(estimate.mean, expected, 0.02 * expected) << "x = " << px;
  }
}

// ---- determinism -------------------------------------------------------------------------------

ImageRgbF traceWithThreads(const scene::Scene& scene, const trace::TraceSettings& settings, int threads) {
  const trace::PathTracer tracer(scene, defaultDictionary(), settings);
  tbb::task_arena arena(threads);
  ImageRgbF image;
  arena.execute([&] { image = tracer.render(); });
  return image;
}

TEST(Trace, ImagesDoNotDependOnTheThreadCount) {
  // The sphere (uniform environment, glints) and the car paint (an equirect sky, coloured glints,
  // interreflections between the car and the floor).
  for (const char* name : {"sphere", "carpaint"}) {
    const scene::Scene scene = scene::makeBuiltinScene(name);
    trace::TraceSettings settings;
    settings.width = 40;
    settings.height = 30;
    settings.spp = 2;
    settings.camera = scene.cameras.at("default");
    const ImageRgbF one = traceWithThreads(scene, settings, 1);
    for (int threads : {2, 4}) {
      const ImageRgbF many = traceWithThreads(scene, settings, threads);
      ASSERT_EQ(one.pixels.size(), many.pixels.size());
      EXPECT_EQ(std::memcmp(one.pixels.data(), many.pixels.data(), one.pixels.size() * sizeof(glm::vec3)), 0)
          << name << " on " << threads << " threads";
    }
    double sum = 0.0;
    for (const glm::vec3& p : one.pixels) sum += p.r + p.g + p.b;
    EXPECT_GT(sum, 0.0) << name;
  }
}

// ---- the cross-renderer check ------------------------------------------------------------------

// Direct light from one point light, no environment, both renderers at 128 x 128: the path tracer
// through pixel centres with the footprint from its ray differentials, the rasteriser at one
// sample with the footprint from its screen derivatives: relative MSE (compareImages) of the
// traced image against the rasterised one.
struct CrossCheck {
  double glint;
  double cookTorrance;
  double zirrKaplanyan;
};

// `spot`: the light becomes a spot aimed at the scene's centre whose cones (0.05 and 0.12 radians)
// leave part of the view unlit. `ranged`: the light's range is its distance to the scene's centre,
// so its light fades across the scene and the far side gets none. `coloured`: every vertex gets a
// colour (COLOR_0) that varies with its position, which both renderers interpolate. `transformed`:
// every material's textures get a KHR_texture_transform (offset, rotation and a scale that is not
// uniform), which moves the uv and stretches the footprint of each lookup. `lean`: both renderers
// filter the glint layers' normal maps (the rasteriser's ggaa+lean with the GGAA kernel at 0, so
// that its glints are the tracer's, each at one half vector a pixel); otherwise neither does.
// `gltfTarget`: every material's specular lobe is glTF's (GGX, Smith, multiple-scattering
// compensation: scene::kGltfSpecular) instead of the paper's.
// `shadowCascades`: the rasteriser's directional lights' shadow maps (gl::FrameSettings).
// `rasterFootprint`, `traceFootprint`: each renderer's glint footprint policy (--footprint).
CrossCheck compareRenderers(const scene::Scene& scene, const std::string& label, const scene::Camera& camera,
                            bool lean, bool shadows = true, int shadowCascades = gl::kShadowCascades,
                            FootprintPolicy rasterFootprint = exactFootprintPolicy(),
                            FootprintPolicy traceFootprint = exactFootprintPolicy());

CrossCheck crossRendererRelMse(const std::string& name, bool spot = false, bool orthographic = false,
                               bool ranged = false, bool coloured = false, bool transformed = false,
                               bool lean = false, bool gltfTarget = false,
                               FootprintPolicy rasterFootprint = exactFootprintPolicy(),
                               FootprintPolicy traceFootprint = exactFootprintPolicy(), int lod = -1,
                               bool coated = false) {
  scene::Scene scene = scene::makeBuiltinScene(name);
  if (coated) {
    // KHR_materials_clearcoat over every glint layer: a car paint's smooth clear coat.
    for (scene::Material& m : scene.materials) {
      if (m.glint.enabled) m.clearcoat = {.factor = 1.0f, .roughness = 0.1f};
    }
  }
  if (gltfTarget) {
    for (scene::Material& m : scene.materials) m.specular = scene::kGltfSpecular;
  }
  if (lod >= 0) {
    for (scene::Material& m : scene.materials) m.glint.lod = lod;
  }
  // One point light (the scene's first), black environment: direct light only, in both.
  std::vector<scene::Light> lights;
  for (const scene::Light& light : scene.lights) {
    if (light.type == scene::Light::Type::Point && lights.empty()) lights.push_back(light);
  }
  if (lights.empty() && !scene.lights.empty()) lights.push_back(scene.lights.front());  // no point light: the first
  if (spot) {
    scene::Light& light = lights.at(0);
    light.type = scene::Light::Type::Spot;
    light.direction = glm::normalize(0.5f * (scene.boundsMin() + scene.boundsMax()) - light.position);
    light.innerConeAngle = 0.05f;
    light.outerConeAngle = 0.12f;
  }
  if (ranged) lights.at(0).range = glm::length(0.5f * (scene.boundsMin() + scene.boundsMax()) - lights.at(0).position);
  if (transformed) {
    scene::UvTransform transform;
    transform.offset = glm::vec2(0.3f, -0.1f);
    transform.rotation = 0.4f;
    transform.scale = glm::vec2(1.5f, 0.8f);
    for (scene::Material& m : scene.materials) {
      m.baseColourUv = m.metallicRoughnessUv = m.normalUv = m.emissiveUv = m.occlusionUv = transform;
    }
  }
  if (coloured) {
    for (scene::Mesh& mesh : scene.meshes) {
      for (scene::Vertex& v : mesh.vertices) {
        v.colour = glm::vec4(0.5f + 0.5f * glm::sin(4.0f * v.position), 1.0f);
      }
    }
  }
  scene.lights = lights;
  scene.environment = scene::Environment{};
  const std::string label = name + (spot ? " (spot)" : "") + (orthographic ? " (orthographic)" : "") +
                            (ranged ? " (range)" : "") + (coloured ? " (vertex colours)" : "") +
                            (transformed ? " (texture transform)" : "") + (gltfTarget ? " (GGX, Smith, compensated)" : "") +
                            (coated ? " (clear coat)" : "");
  return compareRenderers(scene, label,
                          orthographic ? orthographicTwin(scene.cameras.at("default")) : scene.cameras.at("default"), lean,
                          true, gl::kShadowCascades, rasterFootprint, traceFootprint);
}

// The cross-renderer check of `scene` as it is, seen by `camera`: the rasteriser with or without
// its shadows (the tracer always has them). `lean` as crossRendererRelMse's.
CrossCheck compareRenderers(const scene::Scene& scene, const std::string& label, const scene::Camera& camera, bool lean,
                            bool shadows, int shadowCascades, FootprintPolicy rasterFootprint,
                            FootprintPolicy traceFootprint) {
  const int size = 128;
  useGlContext();
  gl::Renderer renderer(scene, defaultDictionary());
  CrossCheck result{};
  for (const SpecularModel model : {SpecularModel::Glint, SpecularModel::CookTorrance, SpecularModel::ZirrKaplanyan}) {
    gl::FrameSettings frame;
    frame.width = size;
    frame.height = size;
    frame.brdf = model;
    // The tracer's pixel centres: one half vector a pixel, one sample of the geometry.
    frame.antiAliasing = lean ? gl::AntiAliasing::GgaaLean : gl::AntiAliasing::None;
    frame.filterScale = 0.0f;
    frame.msaa = 1;
    frame.shadows = shadows;
    frame.shadowCascades = shadowCascades;
    frame.camera = camera;
    frame.footprintPolicy = rasterFootprint;
    renderer.renderFrame(frame);
    const std::vector<float> rgba = renderer.readRadiance();
    const ImageRgbF raster = fromRgbaFloat(size, size, rgba.data(), true);

    trace::TraceSettings settings;
    settings.width = size;
    settings.height = size;
    settings.spp = 1;  // no randomness is left: pixel centres, delta lights, no bounces
    settings.directOnly = true;
    settings.pixelCentres = true;
    settings.normalMapFiltering = lean;
    settings.footprintPolicy = traceFootprint;
    settings.brdf = model;
    settings.camera = frame.camera;
    const ImageRgbF traced = trace::PathTracer(scene, defaultDictionary(), settings).render();
    const ImageError error = compareImages(traced, raster);
    std::printf("[ cross    ] %s%s %s: relMSE %.3g, RMSE %.3g, mean %.3g\n", label.c_str(),
                !shadows ? " (rasteriser without shadows)" : shadowCascades == 1 ? " (one shadow map)" : "",
                toString(model), error.relmse, error.rmse, error.meanReference);
    (model == SpecularModel::Glint ? result.glint : model == SpecularModel::CookTorrance ? result.cookTorrance
                                                                                          : result.zirrKaplanyan) = error.relmse;
  }
  return result;
}

TEST(TraceGl, DirectLightMatchesTheRealTimeRenderer) {
  // Measured 2026-11-22 on Mesa llvmpipe (LLVM 15), 128 x 128, after the real-time renderer's
  // flat-normal fallback was made exact (it had tilted every normal without a normal map by 0.32
  // degrees, which gave 8.7e-5 and 2.9e-3 here before):
  //   sphere   glint 1.6e-5, Cook-Torrance 1.6e-5
  //   parquet  glint 2.9e-4, Cook-Torrance 2.5e-5
  //   sphere under a spot (its cones cut the sphere: mean radiance 0.0106 against 0.029)
  //            glint 9.2e-8, Cook-Torrance 2.4e-11 (the cone leaves the silhouette unlit, where the
  //            two renderers differ most)
  //   the same with an orthographic camera framing the scene alike (added 2026-11-22):
  //            sphere glint 3.8e-7, Cook-Torrance 3.7e-7; parquet glint 4.0e-4, Cook-Torrance
  //            3.6e-5. A perspective view vector under the parallel projection gives 1.7e-2 and
  //            2.5e-1 (glint).
  // What remains is texture filtering (llvmpipe: LOD per 2 x 2 quad, 8-bit weights) and float
  // arithmetic; glints at the parquet's small alphas react to direction most. The footprint itself
  // agrees: one-sided differences forwards or backwards change the traced images by 2.5e-5.
  // Bounds: about three times the measurements, still far below what a wrong footprint gives
  // (measured: footprint x1.25 gives 4.6e-4 on the sphere and 7.2e-3 on the parquet).
  struct Bound {
    const char* scene;
    double glint;
    double cookTorrance;
    bool spot = false;
    bool orthographic = false;
    bool ranged = false;
    bool coloured = false;
    bool transformed = false;
    bool lean = false;
    bool gltfTarget = false;
    bool coated = false;
  };
  for (const Bound& bound : {Bound{"sphere", 5e-5, 5e-5}, Bound{"parquet", 1e-3, 1e-4}, Bound{"sphere", 5e-5, 5e-5, true},
                             Bound{"sphere", 5e-5, 5e-5, false, true}, Bound{"parquet", 1e-3, 1e-4, false, true},
                             Bound{"sphere", 5e-5, 5e-5, false, false, true}, Bound{"sphere", 5e-5, 5e-5, false, false, false, true},
                             Bound{"parquet", 1e-3, 1e-4, false, false, false, false, true},
                             // glTF's lobe: GGX glints (scale mixture), Smith, the compensation.
                             Bound{"sphere", 5e-5, 5e-5, false, false, false, false, false, false, true},
                             Bound{"parquet", 1e-3, 1e-4, false, false, false, false, false, false, true},
                             // Coloured glints (the car paint's random cell colours), tinted once in each:
                             // measured 2026-12-03 glint 1.2e-4, Cook-Torrance 1.2e-4 (the car's shadow
                             // edges on the floor); the path tracer tinting twice gave glint 1.1e-3.
                             Bound{"carpaint", 3e-4, 3e-4},
                             // Under a clear coat (KHR_materials_clearcoat, roughness 0.1), as uncoated:
                             // measured 2026-12-07 car paint glint 1.17e-4, sphere 5.8e-7; with the
                             // tracer ignoring the coat 3.5e-4 and 3.7e-3.
                             Bound{"carpaint", 3e-4, 3e-4, false, false, false, false, false, false, false, true},
                             Bound{"sphere", 5e-5, 5e-5, false, false, false, false, false, false, false, true}}) {
    const CrossCheck relMse =
        crossRendererRelMse(bound.scene, bound.spot, bound.orthographic, bound.ranged, bound.coloured, bound.transformed,
                            bound.lean, bound.gltfTarget, exactFootprintPolicy(), exactFootprintPolicy(), -1, bound.coated);
    std::printf("%s%s: path tracer vs real-time renderer, direct light, relMSE glint %.2e, Cook-Torrance %.2e, "
                "Zirr & Kaplanyan %.2e\n",
                bound.scene, bound.lean ? " (normal maps filtered)" : bound.coated ? " (clear coat)" : "", relMse.glint, relMse.cookTorrance,
                relMse.zirrKaplanyan);
    EXPECT_LT(relMse.glint, bound.glint) << bound.scene;
    EXPECT_LT(relMse.cookTorrance, bound.cookTorrance) << bound.scene;
    // Zirr & Kaplanyan 2016 in both (the tracer's since 2026-12-07): measured on the sphere 6.3e-7
    // (spot 1.8e-7, orthographic 3.8e-7, glTF's lobe 6.2e-7; 8.9e-6 while the tracer's lacked the
    // target's multiple-scattering compensation, which the rasteriser adds), the car paint 1.2e-4 (the shadow
    // edges, as glint's), the parquet 5.6e-3 (orthographic 7.2e-3): at the parquet's small alphas
    // its sparse, bright microdetails react to the two renderers' footprints (quad derivatives, ray
    // differentials) twenty times more than glint's glints do. Bounds about three times those.
    const double zirrKaplanyanBound = std::string(bound.scene) == "parquet" ? 2e-2 : bound.glint;
    EXPECT_LT(relMse.zirrKaplanyan, zirrKaplanyanBound) << bound.scene;
  }
}

// The rasteriser's image of `scene` seen by `camera`, one sample a pixel, without anti-aliasing.
ImageRgbF rasterImage(const scene::Scene& scene, const scene::Camera& camera, int size, SpecularModel brdf) {
  useGlContext();
  gl::Renderer renderer(scene, defaultDictionary());
  gl::FrameSettings frame;
  frame.width = size;
  frame.height = size;
  frame.brdf = brdf;
  frame.antiAliasing = gl::AntiAliasing::None;
  frame.msaa = 1;
  frame.camera = camera;
  renderer.renderFrame(frame);
  const std::vector<float> rgba = renderer.readRadiance();
  return fromRgbaFloat(size, size, rgba.data(), true);
}

// The path tracer's direct light at pixel centres (no randomness left), as the rasteriser draws it.
ImageRgbF directLightAtPixelCentres(const scene::Scene& scene, const scene::Camera& camera, int size, SpecularModel brdf) {
  trace::TraceSettings settings;
  settings.width = size;
  settings.height = size;
  settings.spp = 1;
  settings.directOnly = true;
  settings.pixelCentres = true;
  settings.brdf = brdf;
  settings.camera = camera;
  return trace::PathTracer(scene, defaultDictionary(), settings).render();
}

// A quantized mesh's uv (KHR_mesh_quantization: integers, brought to [0, 1] by the base colour
// texture's KHR_texture_transform, as in the quantized Duck): the glint layer lies in the
// transformed uv, so the density glint estimates for it and both renderers' glints are the plain
// mesh's. The sphere with its uv times 1000 and a transform scaling them back: the estimate equal to
// 0.1 (its rounding), each renderer's image within relMSE 1e-4 of the plain one's (float rounding of
// uv x 1000 x 0.001 moves a few cell boundaries). Before, the layer read the raw uv: the estimate
// fell from 15.5 to its floor and the glints were another pattern at other levels.
TEST(TraceGl, AQuantizedMeshGlintsAsThePlainOne) {
  const scene::Scene plain = [] {
    scene::Scene s = scene::makeBuiltinScene("sphere");
    s.lights.resize(1);
    s.environment = scene::Environment{};
    return s;
  }();
  scene::Scene quantized = plain;
  for (scene::Mesh& mesh : quantized.meshes) {
    for (scene::Vertex& v : mesh.vertices) v.uv = glm::round(v.uv * 1000.0f);
  }
  for (scene::Material& m : quantized.materials) m.baseColourUv.scale = glm::vec2(0.001f);
  int layered = 0;
  for (std::size_t i = 0; i < plain.materials.size(); ++i) {
    if (!plain.materials[i].glint.enabled) continue;
    ++layered;
    const float expected = scene::visibleGlintDensity(plain, static_cast<int>(i)).logDensity;
    EXPECT_NEAR(scene::visibleGlintDensity(quantized, static_cast<int>(i)).logDensity, expected, 0.1f) << plain.materials[i].name;
    EXPECT_GT(expected, kMinLogDensity + 1.0f);
  }
  ASSERT_GT(layered, 0);
  const scene::Camera& camera = plain.cameras.at("default");
  auto raster = [&](const scene::Scene& scene) { return rasterImage(scene, camera, 128, SpecularModel::Glint); };
  auto traced = [&](const scene::Scene& scene) { return directLightAtPixelCentres(scene, camera, 128, SpecularModel::Glint); };
  const ImageError rasterError = compareImages(raster(quantized), raster(plain));
  const ImageError traceError = compareImages(traced(quantized), traced(plain));
  std::printf("quantized uv against plain: relMSE rasteriser %.2e, path tracer %.2e\n", rasterError.relmse, traceError.relmse);
  EXPECT_LT(rasterError.relmse, 1e-4);
  EXPECT_LT(traceError.relmse, 1e-4);
}

// glTF samplers (textures[].sampler) in both renderers: a 4 x 4 checker of four colours on a quad
// whose uv run from -1 to 2, so that the wrap modes show beyond [0, 1] and the texels are magnified
// about 20 times. Under each sampler the two renderers agree within relMSE 1e-3 (measured
// 2026-12-07: at most 4.3e-6, clamp's bilinear edges under llvmpipe's 8-bit filter weights), and
// each sampler's image differs from the default's (repeat, linear) by over 1e-2 (measured 0.12 to
// 0.79): before samplers were read, both renderers drew every variant as the default.
TEST(TraceGl, SamplersWrapAndFilterAsTheFileSays) {
  using Wrap = scene::TextureSampler::Wrap;
  scene::Scene base;
  base.name = "samplers";
  scene::Texture checker;
  checker.name = "checker";
  checker.width = 4;
  checker.height = 4;
  const glm::u8vec4 colours[4] = {{230, 40, 40, 255}, {40, 200, 60, 255}, {50, 70, 220, 255}, {240, 240, 240, 255}};
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const glm::u8vec4 c = colours[(x + 2 * y + x * y) % 4];
      checker.rgba.insert(checker.rgba.end(), {c.r, c.g, c.b, c.a});
    }
  }
  base.textures.push_back(checker);
  scene::Material material;
  material.name = "checker";
  material.baseColourTexture = 0;
  material.roughness = 1.0f;
  base.materials.push_back(material);
  scene::Mesh quad = scene::makeQuad("quad", 0, glm::vec3(0.0f), {1, 0, 0}, {0, -1, 0}, glm::vec2(3.0f));  // facing +z
  for (scene::Vertex& v : quad.vertices) v.uv -= glm::vec2(1.0f);
  base.meshes.push_back(quad);
  scene::Light sun;
  sun.type = scene::Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(0.2f, -0.3f, -1.0f));
  sun.intensity = glm::vec3(3.0f);
  base.lights.push_back(sun);
  base.environment = scene::Environment{};
  scene::Camera camera;
  camera.position = glm::vec3(0.0f, 0.0f, 2.6f);
  camera.target = glm::vec3(0.0f);
  base.cameras["default"] = camera;
  auto render = [&](const scene::Scene& scene) {
    return std::pair{rasterImage(scene, camera, 128, SpecularModel::CookTorrance),
                     directLightAtPixelCentres(scene, camera, 128, SpecularModel::CookTorrance)};
  };
  const auto [defaultRaster, defaultTraced] = render(base);
  const ImageError defaultAgreement = compareImages(defaultTraced, defaultRaster);
  EXPECT_LT(defaultAgreement.relmse, 1e-3);
  EXPECT_GT(defaultAgreement.meanReference, 0.05);  // lit
  struct Variant {
    const char* name;
    scene::TextureSampler sampler;
  };
  const Variant variants[] = {{"clamp", {.wrapS = Wrap::ClampToEdge, .wrapT = Wrap::ClampToEdge}},
                              {"mirror", {.wrapS = Wrap::MirroredRepeat, .wrapT = Wrap::Repeat}},
                              {"nearest", {.magnifyNearest = true}},
                              {"clamp and mirror, nearest", {.wrapS = Wrap::ClampToEdge, .wrapT = Wrap::MirroredRepeat,
                                                             .magnifyNearest = true, .minifyNearest = true,
                                                             .mipmap = scene::TextureSampler::Mipmap::None}}};
  for (const Variant& variant : variants) {
    scene::Scene scene = base;
    scene.textures[0].sampler = variant.sampler;
    const auto [raster, traced] = render(scene);
    const double agreement = compareImages(traced, raster).relmse;
    const double change = compareImages(raster, defaultRaster).relmse;
    std::printf("sampler %s: relMSE tracer against rasteriser %.2e; against the default sampler %.2e\n", variant.name,
                agreement, change);
    EXPECT_LT(agreement, 1e-3) << variant.name;
    EXPECT_GT(change, 1e-2) << variant.name;
  }
}

TEST(TraceGl, RenderersAgreeUnderAFootprintPolicy) {
  // Both renderers under aniso=2,cells=12,drop=0.5 (every word, each compiled into the rasteriser's
  // program; the LOD raised on nearly every pixel, the coarser level dropped on half of them): they
  // agree within the bounds of DirectLightMatchesTheRealTimeRenderer
  // (the sphere 5e-5, the parquet's small alphas 1e-3). The same policy on the rasteriser alone,
  // against the tracer's exact footprint, is far outside them: another footprint shows other glints.
  const FootprintPolicy policy = footprintPolicyFromString("aniso=2,cells=12,drop=0.5");
  for (const auto& [name, bound] : {std::pair<const char*, double>{"sphere", 5e-5}, {"parquet", 1e-3}}) {
    const CrossCheck both = crossRendererRelMse(name, false, false, false, false, false, false, false, policy, policy);
    const CrossCheck rasterOnly =
        crossRendererRelMse(name, false, false, false, false, false, false, false, policy, exactFootprintPolicy());
    std::printf("%s under %s: relMSE glint %.2e (rasteriser alone under it: %.2e)\n", name,
                footprintPolicyName(policy).c_str(), both.glint, rasterOnly.glint);
    EXPECT_LT(both.glint, bound) << name;
    EXPECT_LT(both.cookTorrance, bound) << name;
    EXPECT_GT(rasterOnly.glint, 10.0 * bound) << name;
  }
}

TEST(TraceGl, RenderersAgreeUnderTheTreeLod) {
  // Both renderers under the tree LOD construction (docs/method.md 2.8; the rasteriser's program
  // compiled for it): within the bounds of DirectLightMatchesTheRealTimeRenderer.
  const FootprintPolicy exact = exactFootprintPolicy();
  for (const auto& [name, bound] : {std::pair<const char*, double>{"sphere", 5e-5}, {"parquet", 1e-3}}) {
    const CrossCheck tree =
        crossRendererRelMse(name, false, false, false, false, false, false, false, exact, exact, kernel::GLINT_LOD_TREE);
    std::printf("%s, tree LOD: relMSE glint %.2e, Cook-Torrance %.2e\n", name, tree.glint, tree.cookTorrance);
    EXPECT_LT(tree.glint, bound) << name;
    EXPECT_LT(tree.cookTorrance, bound) << name;
  }
}

TEST(TraceGl, NormalMapFilteringMakesTheRenderersAgreeOnNormalMappedGlints) {
  // The arctic snow: roughness 0.05 on a normal map with several texels a pixel, lit by a low sun.
  // Each renderer filters the normal texture at its own footprint (llvmpipe per 2 x 2 quad, the
  // tracer from its ray differentials), and at such a roughness a highlight follows the normal so
  // closely that their pixels disagree (measured 2026-12-01: relMSE glint 9.75, Cook-Torrance 1.11).
  // With normal-map filtering in both, the slopes' variance, which both measure alike, replaces
  // what neither resolves: relMSE glint 6.5e-2, 150 times closer. With the rasteriser's shadows
  // the low sun's shadows of the snowman and the ornament fall on the snow in both renderers, and
  // how sharp the rasteriser's are decides the figure (measured 2026-12-02): from one directional
  // map fit to the whole 64 m field (3 cm texels, filtered edges some 30 cm wide on the ground at
  // the sun's 12 degrees where the tracer's are hard) the ornament's 6 cm rings cast shadows 1.5
  // texels wide, faint where the tracer's are black: 9.85 unfiltered, 0.208 filtered (8192-texel
  // maps: 0.089). With the cascades (docs/renderer.md, "Shadows") the ground the rings' shadows
  // fall on, 3 to 5 m from the camera, is in cascades of millimetre texels: 9.70 and 6.33e-3,
  // 1500 times closer. relMSE divides by the rasteriser's value, so a thin shadow left out costs
  // little and one drawn faint costs much. Bound: 0.2 and 20 times closer.
  const CrossCheck unfiltered = crossRendererRelMse("arctic");
  const CrossCheck filtered = crossRendererRelMse("arctic", false, false, false, false, false, true);
  std::printf("arctic: relMSE glint %.3g unfiltered, %.3g with normal maps filtered\n", unfiltered.glint, filtered.glint);
  EXPECT_LT(filtered.glint, 0.2);
  EXPECT_LT(20.0 * filtered.glint, unfiltered.glint);
}

// ---- shadows -----------------------------------------------------------------------------------

// A 4 x 4 m floor and, 1 m above it, a 0.6 m square plate, both grey and diffuse-looking
// (Cook-Torrance at roughness 0.6), a black environment, and one light of the given type at
// (-1, 3, 0) (a directional one shining the same way) aimed so that the plate's shadow covers
// x in [0.05, 0.95], z in [-0.45, 0.45] on the floor ([0.2, 0.8] and [-0.3, 0.3] for the
// directional one). The camera looks straight down at (0.5, 0, 0), the middle of the shadow,
// past the plate's edge.
// A grey floor of half side floorHalf about the origin and a square plate of half side plateHalf
// centred at plateCentre, both horizontal, one rough grey material, no lights or camera yet.
scene::Scene floorAndPlate(const std::string& name, float floorHalf, glm::vec3 plateCentre, float plateHalf) {
  scene::Scene s;
  s.name = name;
  scene::Material grey;
  grey.baseColour = glm::vec4(0.8f, 0.8f, 0.8f, 1.0f);
  grey.roughness = 0.6f;
  s.materials.push_back(grey);
  s.meshes.push_back(scene::makeQuad("floor", 0, glm::vec3(0.0f), {floorHalf, 0.0f, 0.0f}, {0.0f, 0.0f, floorHalf}));
  s.meshes.push_back(scene::makeQuad("plate", 0, plateCentre, {plateHalf, 0.0f, 0.0f}, {0.0f, 0.0f, plateHalf}));
  return s;
}

scene::Scene occluderScene(scene::Light::Type type) {
  scene::Scene s = floorAndPlate("occluder", 2.0f, glm::vec3(0.0f, 1.0f, 0.0f), 0.3f);
  scene::Light light;
  light.type = type;
  light.position = glm::vec3(-1.0f, 3.0f, 0.0f);
  light.direction = glm::normalize(glm::vec3(0.5f, 0.0f, 0.0f) - light.position);
  light.intensity = glm::vec3(type == scene::Light::Type::Directional ? 1.5f : 20.0f);
  light.innerConeAngle = 0.5f;
  light.outerConeAngle = 0.6f;
  s.lights = {light};
  scene::Camera camera;
  camera.position = glm::vec3(0.5f, 4.0f, 0.0f);
  camera.target = glm::vec3(0.5f, 0.0f, 0.0f);
  camera.up = glm::vec3(0.0f, 0.0f, -1.0f);
  camera.verticalFovDegrees = 60.0f;
  s.cameras["default"] = camera;
  return s;
}

const char* lightTypeName(scene::Light::Type type) {
  return type == scene::Light::Type::Point ? "point" : type == scene::Light::Type::Spot ? "spot" : "directional";
}

// In both renderers, direct light only, the floor in the middle of the plate's shadow gets less
// than 1% of the radiance of the floor at (0.5, 0, 1.2), outside it (both the same distance from
// the light's axis plane, so a missing shadow would show as about the same radiance). The
// rasteriser without shadows (the test fails then) and the tracer, whose shadow rays always run.
void expectTheShadowBehindThePlate(scene::Light::Type type) {
  const scene::Scene scene = occluderScene(type);
  const scene::Camera& camera = scene.cameras.at("default");
  constexpr int kSide = 64;
  useGlContext();
  gl::Renderer renderer(scene, defaultDictionary());
  gl::FrameSettings frame;
  frame.width = kSide;
  frame.height = kSide;
  frame.brdf = SpecularModel::CookTorrance;
  frame.msaa = 1;
  frame.camera = camera;
  renderer.renderFrame(frame);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
  const std::vector<float> rgba = renderer.readRadiance();
  const ImageRgbF raster = fromRgbaFloat(kSide, kSide, rgba.data(), true);
  trace::TraceSettings settings;
  settings.width = kSide;
  settings.height = kSide;
  settings.spp = 1;
  settings.directOnly = true;
  settings.pixelCentres = true;
  settings.brdf = SpecularModel::CookTorrance;
  settings.camera = camera;
  const ImageRgbF traced = trace::PathTracer(scene, defaultDictionary(), settings).render();

  const glm::mat4 viewProjection =
      gl::viewProjection(camera, kSide, kSide, glm::vec2(0.0f), scene.boundsMin(), scene.boundsMax());
  auto radianceAt = [&](const ImageRgbF& image, glm::vec3 point) {
    const glm::vec4 clip = viewProjection * glm::vec4(point, 1.0f);
    const int x = static_cast<int>((0.5f * clip.x / clip.w + 0.5f) * kSide);
    const int y = kSide - 1 - static_cast<int>((0.5f * clip.y / clip.w + 0.5f) * kSide);  // rows from the top
    const glm::vec3 c = image.at(x, y);
    return (c.r + c.g + c.b) / 3.0f;
  };
  const glm::vec3 shadowed(0.5f, 0.0f, 0.0f);
  const glm::vec3 lit(0.5f, 0.0f, 1.2f);
  for (const auto& [name, image] : {std::pair<const char*, const ImageRgbF*>{"rasteriser", &raster}, {"path tracer", &traced}}) {
    const float dark = radianceAt(*image, shadowed);
    const float bright = radianceAt(*image, lit);
    std::printf("%s light, %s: %.3g behind the plate, %.3g beside its shadow\n", lightTypeName(type), name, dark, bright);
    EXPECT_GT(bright, 0.05f) << lightTypeName(type) << ", " << name;
    EXPECT_LT(dark, 0.01f * bright) << lightTypeName(type) << ", " << name;
  }
}

TEST(TraceGl, APointBehindAnOccluderIsDarkUnderADirectionalLight) {
  expectTheShadowBehindThePlate(scene::Light::Type::Directional);
}

TEST(TraceGl, APointBehindAnOccluderIsDarkUnderASpotLight) { expectTheShadowBehindThePlate(scene::Light::Type::Spot); }

TEST(TraceGl, APointBehindAnOccluderIsDarkUnderAPointLight) { expectTheShadowBehindThePlate(scene::Light::Type::Point); }

TEST(TraceGl, ShadowedDirectLightMatchesTheTracer) {
  // The occluder scene under each light type, and the showroom under its key light (the sphere and
  // its stage shadow the parquet, the car the floor): relMSE of the tracer's direct light against
  // the rasteriser's at 128 x 128, pixel centres, with the rasteriser's shadows and without (the
  // tracer always has them). Measured 2026-12-02 on Mesa llvmpipe (LLVM 15), with / without:
  //   occluder, directional  1.2e-14 / 1.4e-2  (2 mm texels: no pixel centre falls in a ramp)
  //   occluder, spot         1.9e-4  / 2.7e-2
  //   occluder, point        2.0e-3  / 2.7e-2  (the cube's texels are 3 times the spot map's)
  //   showroom, key light    Cook-Torrance 1.5e-4 / 5.3e-3, glint 5.7e-4 / 5.7e-3
  // What remains is the filtered edges' ramp (two texels wide where the tracer's edge is hard)
  // and, on the showroom, what the unshadowed check has too (TraceGl.DirectLightMatches...).
  // Bounds: about three times the measurements, and at least three times below what the
  // rasteriser without shadows gives, so that each case fails without them.
  struct Case {
    std::string label;
    scene::Scene scene;
    double bound;
  };
  std::vector<Case> cases;
  const std::pair<scene::Light::Type, double> types[] = {
      {scene::Light::Type::Directional, 1e-4}, {scene::Light::Type::Spot, 1e-3}, {scene::Light::Type::Point, 6e-3}};
  for (const auto& [type, bound] : types) {
    cases.push_back({std::string("occluder, ") + lightTypeName(type) + " light", occluderScene(type), bound});
  }
  scene::Scene showroom = scene::makeBuiltinScene("showroom");
  showroom.lights.resize(1);  // the key light
  showroom.environment = scene::Environment{};
  cases.push_back({"showroom, key light", showroom, 1.7e-3});
  for (const Case& c : cases) {
    const CrossCheck with = compareRenderers(c.scene, c.label, c.scene.cameras.at("default"), false, true);
    const CrossCheck without = compareRenderers(c.scene, c.label, c.scene.cameras.at("default"), false, false);
    std::printf("%s: relMSE Cook-Torrance %.2e with shadows, %.2e without; glint %.2e, %.2e (bound %.1e)\n",
                c.label.c_str(), with.cookTorrance, without.cookTorrance, with.glint, without.glint, c.bound);
    EXPECT_LT(with.cookTorrance, c.bound) << c.label;
    EXPECT_LT(with.glint, c.bound) << c.label;
  }
}

TEST(TraceGl, CascadedShadowMapsResolveASmallOccluderInALargeScene) {
  // A 200 x 200 m grey floor and, 10 cm above it, a 20 cm square plate 1.4 m from the camera,
  // under a directional light 45 degrees up whose shadow of the plate falls beside it, seen from
  // the side (128 x 128, pixel centres, direct light; the tracer's shadow rays are exact). One map
  // fit to the whole floor has 10 cm texels, so the plate's shadow is two texels wide and its
  // filtered edges blur it into a faint smudge; the nearest cascade over the 6 m the camera sees
  // first has texels of a few millimetres. Measured 2026-12-02 on Mesa llvmpipe (LLVM 15):
  // relMSE 3.6e-4 with the cascades, 1.4e-2 with one map (--shadow-cascades 1), both BRDFs (the
  // grey has no glint layer). Bound: about three times the cascades' figure, ten times below the
  // one map's, so that the test fails without cascades.
  scene::Scene s = floorAndPlate("large floor", 100.0f, glm::vec3(0.0f, 0.1f, 0.1f), 0.1f);
  scene::Light light;
  light.type = scene::Light::Type::Directional;
  light.direction = glm::normalize(glm::vec3(0.0f, -1.0f, -1.0f));  // the plate's shadow is centred on the origin
  light.intensity = glm::vec3(1.5f);
  s.lights = {light};
  scene::Camera camera;
  camera.position = glm::vec3(1.0f, 1.0f, 0.0f);
  camera.target = glm::vec3(0.0f, 0.05f, 0.05f);
  camera.verticalFovDegrees = 45.0f;
  s.cameras["default"] = camera;
  const CrossCheck cascades = compareRenderers(s, "large floor", camera, false, true);
  const CrossCheck oneMap = compareRenderers(s, "large floor", camera, false, true, 1);
  std::printf("large floor: relMSE Cook-Torrance %.2e with cascades, %.2e with one map; glint %.2e, %.2e\n",
              cascades.cookTorrance, oneMap.cookTorrance, cascades.glint, oneMap.glint);
  EXPECT_LT(cascades.cookTorrance, 1.2e-3);
  EXPECT_LT(cascades.glint, 1.2e-3);
}

// ---- the command -------------------------------------------------------------------------------

TEST(TraceCli, WritesAnExrAndAPngBesideIt) {
  const auto folder = temporaryFolder("trace_cli");
  const RunResult result = runGlint(folder, "trace sphere -o out.exr --size 40x24 --spp 2 --max-depth 2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find("samples/s"), std::string::npos) << result.err;
  const ImageRgbF exr = readImage(folder / "out.exr");
  EXPECT_EQ(exr.width, 40);
  EXPECT_EQ(exr.height, 24);
  const ImageRgbF png = readImage(folder / "out.png");
  EXPECT_EQ(png.width, 40);
  EXPECT_EQ(png.height, 24);
  // The same command on one thread writes the same file.
  const RunResult again = runGlint(folder, "trace sphere -o one.exr --size 40x24 --spp 2 --max-depth 2 --threads 1");
  ASSERT_EQ(again.exitCode, 0) << again.err;
  EXPECT_EQ(slurp(folder / "out.exr"), slurp(folder / "one.exr"));
  const RunResult modes = runGlint(
      folder, "trace parquet -o modes.exr --size 24x24 --direct-only --pixel-centres --brdf cook-torrance --sampler gaussian");
  ASSERT_EQ(modes.exitCode, 0) << modes.err;
  EXPECT_NE(modes.err.find("direct light only"), std::string::npos) << modes.err;
  // Zirr & Kaplanyan, as the rasteriser draws it (TraceGl.DirectLightMatchesTheRealTimeRenderer
  // compares the images), with its bounces sampled through its smooth lobe.
  const RunResult zirrKaplanyan = runGlint(folder, "trace sphere -o zk.exr --size 24x24 --spp 4 --brdf zirr-kaplanyan");
  ASSERT_EQ(zirrKaplanyan.exitCode, 0) << zirrKaplanyan.err;
  EXPECT_NE(zirrKaplanyan.err.find("zirr-kaplanyan"), std::string::npos) << zirrKaplanyan.err;
}

TEST(TraceCli, BadOptionsAndScenesGiveOneLineAndNoFile) {
  const auto folder = temporaryFolder("trace_errors");
  const std::pair<std::string, std::string> cases[] = {
      {"sphere --spp 0 --size 16x16", "--spp"},
      {"sphere --size 0x5", "--size"},
      {"sphere --size big", "--size"},
      {"sphere --max-depth 0 --size 16x16", "--max-depth"},
      {"sphere --sampler metropolis --size 16x16", "unknown sampler 'metropolis'"},
      {"sphere --brdf phong --size 16x16", "unknown BRDF 'phong'"},
      {"sphere --camera nowhere --size 16x16", "no camera 'nowhere'"},
      {"nosuchscene --size 16x16", "unknown scene 'nosuchscene'"},
      {"sphere --exposure -1 --size 16x16", "--exposure"},
      {"sphere --threads -2 --size 16x16", "--threads"},
      {"sphere --log-density 500 --size 16x16", "--log-density: log_density must be in [0, 100], got 500"},
      {"sphere --alpha 5 --size 16x16", "--alpha: alpha_x must be in [0.005, 2], got 5"},
      {"sphere --dict missing.bin --size 16x16", "missing.bin"},
  };
  for (const auto& [arguments, problem] : cases) {
    const RunResult result = runGlint(folder, "trace " + arguments + " -o out.exr");
    SCOPED_TRACE(arguments);
    expectOneLineError(result, problem);
    EXPECT_FALSE(std::filesystem::exists(folder / "out.exr"));
    EXPECT_FALSE(std::filesystem::exists(folder / "out.png"));
  }
  const RunResult png = runGlint(folder, "trace sphere -o out.png --size 16x16");
  expectOneLineError(png, "must end in .exr");
  EXPECT_FALSE(std::filesystem::exists(folder / "out.png"));
}

TEST(TraceCli, TheExrAndItsPreviewAreOneOutput) {
  // The preview cannot be written (a folder has its name): the previous EXR must stay as it was,
  // not be replaced by a new one beside a stale preview, and no temporary is left.
  const auto folder = temporaryFolder("trace_pair");
  std::ofstream(folder / "out.exr") << "previous";
  std::filesystem::create_directory(folder / "out.png");
  // A temporary left by a killed process (no such process) is cleaned up by the next write; one of
  // a live process (pid 1) is not touched.
  std::ofstream(folder / "out.exr.tmp999999999") << "stale";
  std::ofstream(folder / "out.exr.tmp1") << "live";
  expectOneLineError(runGlint(folder, "trace sphere -o out.exr --size 16x16 --spp 1"), "out.png: cannot write (is a directory)");
  EXPECT_EQ(slurp(folder / "out.exr"), "previous");
  std::filesystem::remove(folder / "out.png");
  const RunResult written = runGlint(folder, "trace sphere -o out.exr --size 16x16 --spp 1");
  ASSERT_EQ(written.exitCode, 0) << written.err;
  EXPECT_NE(slurp(folder / "out.exr"), "previous");
  EXPECT_TRUE(std::filesystem::is_regular_file(folder / "out.png"));
  EXPECT_FALSE(std::filesystem::exists(folder / "out.exr.tmp999999999"));
  EXPECT_TRUE(std::filesystem::exists(folder / "out.exr.tmp1"));
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), name == "out.exr.tmp1" ? 7u : std::string::npos) << "left behind: " << name;
  }
}

TEST(TraceCli, ScenesBeyondTheRayRangeAreRefused) {
  // Embree aborts (its ray validity assertion, release builds too) on ray origins beyond about
  // 1.8e18. The sphere scaled so that it and its camera lie near 1e18 must be refused in one line;
  // scaled to 1e12 it traces.
  const auto folder = temporaryFolder("trace_range");
  for (const float scale : {1e18f, 1e12f}) {
    scene::Scene scaled = scene::makeBuiltinScene("sphere");
    for (scene::Mesh& mesh : scaled.meshes) {
      for (scene::Vertex& vertex : mesh.vertices) vertex.position *= scale;
    }
    for (auto& [name, camera] : scaled.cameras) {
      camera.position *= scale;
      camera.target *= scale;
    }
    for (scene::Light& light : scaled.lights) light.position *= scale;
    const std::string file = scale > 1e15f ? "huge.glb" : "large.glb";
    scene::writeGltf(folder / file, scaled);
    const RunResult result = runGlint(folder, "trace " + file + " -o out.exr --size 16x16 --spp 1");
    if (scale > 1e15f) {
      expectOneLineError(result, "beyond the path tracer's range");
      EXPECT_NE(result.err.find("huge.glb"), std::string::npos) << result.err;
      EXPECT_FALSE(std::filesystem::exists(folder / "out.exr"));
    } else {
      EXPECT_EQ(result.exitCode, 0) << result.err;
      std::filesystem::remove(folder / "out.exr");
      std::filesystem::remove(folder / "out.png");
    }
  }
}

}  // namespace
}  // namespace glint
