// The page (web/, docs/web.md) in a real headless browser: Debian's chromium driven by
// tests/web/drive.mjs (puppeteer-core), its WebGL2 on Mesa llvmpipe through ANGLE and on
// SwiftShader. The kernel compiled as GLSL ES must agree with the CPU kernel as the desktop GLSL
// does (tests/kernel_cases.h); the page's frames of the built-in scenes must be the desktop
// renderer's; a broken glTF dropped on the page must be named on the page, the previous scene kept.
// Each test skips with one line when the browser, node's driver or the built page is missing
// (scripts/deps installs the first two; the build makes the page when Emscripten is installed).
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "gl/display.h"
#include "gl/renderer.h"
#include "gl_support.h"
#include "glint/file_io.h"
#include "kernel_cases.h"
#include "scene/area_lights.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/gltf_writer.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;
namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kSite = GLINT_WEB_SITE;  // build/web/site
const fs::path kDriver = fs::path(GLINT_SOURCE_DIR) / "tests" / "web" / "drive.mjs";
const fs::path kChromium = "/usr/bin/chromium";

// What the web tests lack, in one line; empty when they can run.
std::string missingForWebTests() {
  if (!fs::exists(kChromium)) return "chromium is not installed (scripts/deps installs it)";
  if (std::system("node --version >/dev/null 2>&1") != 0) return "node is not installed (scripts/deps installs it)";
  if (!fs::exists(kDriver.parent_path() / "node_modules" / "puppeteer-core")) {
    return "puppeteer-core is not installed in tests/web (scripts/deps installs it)";
  }
  if (!fs::exists(kSite / "glint.wasm") || !fs::exists(kSite / "dictionary.gdict")) {
    return "the page is not built in " + kSite.string() + " (the build makes it when Emscripten is installed: scripts/deps)";
  }
  return "";
}

#define SKIP_WITHOUT_BROWSER()                                              \
  do {                                                                      \
    if (const std::string missing = missingForWebTests(); !missing.empty()) \
      GTEST_SKIP() << "web test skipped: " << missing;                      \
  } while (false)

// A folder for one run of the driver: the job, its input files, its outputs and report.json.
struct BrowserJob {
  fs::path folder;
  json steps = json::array();

  // In the test process's own temporary folder: ctest runs tests side by side.
  explicit BrowserJob(const std::string& name) : folder(temporaryFolder("web-" + name)) {}
  ~BrowserJob() { fs::remove_all(folder); }

  void writeFile(const std::string& name, const void* data, std::size_t size) const {
    std::ofstream(folder / name, std::ios::binary).write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  std::vector<char> readFile(const std::string& name) const {
    std::ifstream in(folder / name, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  // Runs the steps in the page on `backend` (swiftshader or llvmpipe); the driver's report.
  json run(const std::string& backend) const {
    std::ofstream(folder / "job.json") << json{{"steps", steps}}.dump();
    const std::string command = "node '" + kDriver.string() + "' '" + kSite.string() + "' '" + folder.string() + "' " +
                                backend + " 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << command;
    std::ifstream report(folder / "report.json");
    json result = json::parse(report, nullptr, false);
    EXPECT_FALSE(result.is_discarded()) << "no report from " << command;
    if (result.is_discarded()) return json::object();
    // Nothing the page logged as an error, nothing it threw.
    EXPECT_EQ(result["consoleErrors"], json::array()) << backend;
    EXPECT_EQ(result["pageErrors"], json::array()) << backend;
    return result;
  }
};

// The WebGL2 kernel's values of the cases, evaluated in the page.
std::vector<KernelValues> evaluateInBrowser(const std::vector<KernelCase>& cases, bool filtered,
                                            const std::string& backend) {
  BrowserJob job("kernel");
  const std::vector<KernelInput> inputs = kernelInputs(cases);
  job.writeFile("inputs.bin", inputs.data(), inputs.size() * sizeof(KernelInput));
  job.steps.push_back(
      {{"kind", "kernel"}, {"inputs", "inputs.bin"}, {"count", cases.size()}, {"filtered", filtered}, {"output", "out.bin"}});
  job.run(backend);
  const std::vector<char> bytes = job.readFile("out.bin");
  std::vector<KernelValues> values(bytes.size() / sizeof(KernelValues));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(KernelValues));
  return values;
}

// The same kernel sources as GLSL ES 3.00 in WebGL2, on both of chromium's CPU backends, against
// the CPU: the cases and the tolerance of the desktop test (KernelGl.*RandomInputs).
class KernelWeb : public ::testing::TestWithParam<std::string> {};

TEST_P(KernelWeb, WebGl2AndCpuAgreeOnTenThousandRandomInputs) {
  SKIP_WITHOUT_BROWSER();
  const std::vector<KernelCase> cases = randomKernelCases(10000);
  expectCpuAndGpuAgree(cases, false, evaluateInBrowser(cases, false, GetParam()), ("WebGL2 " + GetParam()).c_str());
}

TEST_P(KernelWeb, AntiAliasedWebGl2AndCpuAgreeOnTenThousandRandomInputs) {
  SKIP_WITHOUT_BROWSER();
  const std::vector<KernelCase> cases = randomFilteredKernelCases(10000);
  expectCpuAndGpuAgree(cases, true, evaluateInBrowser(cases, true, GetParam()), ("WebGL2 " + GetParam()).c_str());
}

INSTANTIATE_TEST_SUITE_P(Backends, KernelWeb, ::testing::Values("llvmpipe", "swiftshader"));

// The page's dictionary is the one the desktop tests use: `glint dict` with its defaults.
TEST(PageWeb, DictionaryIsGlintsDefault) {
  SKIP_WITHOUT_BROWSER();
  const Dictionary page = Dictionary::load(kSite / "dictionary.gdict");
  const auto a = page.halfTexels();
  const auto b = defaultDictionary().halfTexels();
  EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin(), b.end()));
}

// A view of a built-in scene the page and the desktop renderer both draw: a BRDF and a cost tier.
struct PageView {
  std::string scene;
  std::string brdf = "glint";
  std::string quality = "exact";
};

// The desktop renderer's 8-bit image of a view of `scene` (what `glint render` writes), RGB.
ImageRgb8 desktopImage(const scene::Scene& scene, const PageView& view, int size) {
  useGlContext();
  gl::Renderer renderer(scene, defaultDictionary());
  gl::FrameSettings frame;
  frame.width = size;
  frame.height = size;
  frame.camera = scene.cameras.at("default");
  frame.brdf = specularModelFromName(view.brdf);
  const gl::QualityPreset& tier = gl::qualityPreset(view.quality);
  frame.footprintPolicy = footprintPolicyFromString(tier.footprint);
  frame.antiAliasing = tier.antiAliasing;
  frame.shadowCascades = tier.shadowCascades;
  frame.shadows = false;  // as the page draws (WebGL2 has no cube-map arrays for point lights' maps)
  const ImageRgbF radiance = gl::renderSupersampled(renderer, frame, 1);
  return gl::DisplayPass().encode(radiance, scene.exposure);
}

ImageRgb8 desktopImage(const PageView& view, int size) {
  return desktopImage(scene::makeBuiltinScene(view.scene), view, size);
}

struct ImageDifference {
  int largest = 0;         // in 8-bit code values, over the channels
  int pixelsDiffering = 0;
  double meanAbsolute = 0.0;  // over the channels
};

// The page's RGBA frame against the desktop renderer's image of the same view.
ImageDifference differenceOf(const std::vector<char>& page, const ImageRgb8& desktop, int size) {
  ImageDifference d;
  long sum = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const auto* p = reinterpret_cast<const unsigned char*>(&page[(static_cast<std::size_t>(y) * size + x) * 4]);
      const auto& q = desktop.at(x, y);
      const int diff[3] = {std::abs(p[0] - q.r), std::abs(p[1] - q.g), std::abs(p[2] - q.b)};
      const int largest = std::max({diff[0], diff[1], diff[2]});
      d.largest = std::max(d.largest, largest);
      d.pixelsDiffering += largest > 0;
      sum += diff[0] + diff[1] + diff[2];
    }
  }
  d.meanAbsolute = static_cast<double>(sum) / (3.0 * size * size);
  return d;
}

// The views in the page against the desktop renderer on llvmpipe; `report` gets the driver's.
ImageDifference comparePageViews(const std::vector<PageView>& views, const std::string& backend, int size,
                                 json* report = nullptr) {
  BrowserJob job("scenes-" + backend);
  for (std::size_t s = 0; s < views.size(); ++s) {
    job.steps.push_back({{"kind", "scene"}, {"name", views[s].scene}, {"brdf", views[s].brdf},
                         {"quality", views[s].quality}, {"width", size}, {"height", size},
                         {"output", std::to_string(s) + ".rgba"}});
  }
  const json result = job.run(backend);
  if (report) *report = result;
  ImageDifference total;
  for (std::size_t s = 0; s < views.size(); ++s) {
    const PageView& view = views[s];
    const std::string label = view.scene + ", " + view.brdf + ", quality " + view.quality;
    if (result.contains("steps") && result["steps"].size() > s) {
      EXPECT_EQ(result["steps"][s]["error"], "") << label << ": the page says so";
    }
    const std::vector<char> page = job.readFile(std::to_string(s) + ".rgba");
    if (page.size() != static_cast<std::size_t>(size) * size * 4) {
      ADD_FAILURE() << label << ": no frame from the page";
      continue;
    }
    const ImageDifference d = differenceOf(page, desktopImage(view, size), size);
    std::printf("%s, %s, %dx%d: %d pixels differ from the desktop renderer's, by at most %d/255, %.4f/255 on average\n",
                backend.c_str(), label.c_str(), size, size, d.pixelsDiffering, d.largest, d.meanAbsolute);
    total.largest = std::max(total.largest, d.largest);
    total.pixelsDiffering += d.pixelsDiffering;
    total.meanAbsolute = std::max(total.meanAbsolute, d.meanAbsolute);
  }
  return total;
}

// Every small built-in scene in the page against the desktop renderer on llvmpipe, with the glint BRDF;
// and the sphere and the car paint with the other two (the Zirr & Kaplanyan program uses the
// prelude's GLSL ES glintFindLSB and glintLdexp, written out where ES 3.00 lacks the built-ins).
ImageDifference compareBuiltinScenes(const std::string& backend, int size) {
  std::vector<PageView> views;
  for (const std::string& name : smallBuiltinSceneNames()) views.push_back({name});
  for (const char* brdf : {"cook-torrance", "zirr-kaplanyan"}) {
    views.push_back({"sphere", brdf});
    views.push_back({"carpaint", brdf});
  }
  return comparePageViews(views, backend, size);
}

// ANGLE on llvmpipe runs the desktop's Mesa: the page's frames are the desktop renderer's, bit for
// bit.
TEST(PageWeb, BuiltinScenesOnLlvmpipeAreTheDesktopRenderersImages) {
  SKIP_WITHOUT_BROWSER();
  const ImageDifference d = compareBuiltinScenes("llvmpipe", 128);
  EXPECT_EQ(d.pixelsDiffering, 0);
}

// The scenes at the paper's scale fit the page's memory and draw as on the desktop, and each cost
// tier chosen in the page's list draws what `--quality` draws (and shows its anti-aliasing).
TEST(PageWeb, PaperScaleScenesAndCostTiersAreTheDesktopRenderersImages) {
  SKIP_WITHOUT_BROWSER();
  std::vector<PageView> views = {{"atrium"}, {"car"}};
  for (const gl::QualityPreset& tier : gl::qualityPresets()) views.push_back({"grazing-rough", "glint", tier.name});
  json report;
  const ImageDifference d = comparePageViews(views, "llvmpipe", 96, &report);
  EXPECT_EQ(d.pixelsDiffering, 0);
  ASSERT_EQ(report["steps"].size(), views.size()) << report.dump();
  for (std::size_t s = 0; s < views.size(); ++s) {
    EXPECT_EQ(report["steps"][s]["antiAliasing"], gl::toString(gl::qualityPreset(views[s].quality).antiAliasing));
  }
  // The memory after the car, the largest scene: under WebAssembly's 2 GiB without MAXIMUM_MEMORY.
  const double memory = report["steps"][1]["memoryBytes"].get<double>();
  std::printf("the page's WebAssembly memory after the atrium and the car: %.0f MiB\n", memory / (1 << 20));
  EXPECT_LT(memory, 2048.0 * (1 << 20));
}

// A broken glTF (its JSON cut short) dropped on the page: the page names the file and the problem
// (the line `glint render` prints), keeps the scene it had, and nothing is logged as an error or
// thrown (BrowserJob::run); a good one dropped after it is shown.
TEST(PageWeb, ABrokenGltfDroppedOnThePageIsNamedAndThePreviousSceneKept) {
  SKIP_WITHOUT_BROWSER();
  BrowserJob job("drop");
  const std::string broken = R"({"asset": {"version": "2.0"}, "scenes": [)";  // cut short
  job.writeFile("broken.gltf", broken.data(), broken.size());
  const std::vector<std::byte> good = scene::encodeGltf(scene::makeBuiltinScene("sphere"), scene::GltfEncoding::Binary);
  job.writeFile("good.glb", good.data(), good.size());
  job.steps.push_back({{"kind", "scene"}, {"name", "carpaint"}, {"width", 64}, {"height", 64}, {"output", "before.rgba"}});
  job.steps.push_back({{"kind", "drop"}, {"file", "broken.gltf"}});
  job.steps.push_back({{"kind", "drop"}, {"file", "good.glb"}});
  const json report = job.run("swiftshader");
  ASSERT_EQ(report["steps"].size(), 3u) << report.dump();
  const json& dropBroken = report["steps"][1];
  const std::string error = dropBroken["error"];
  EXPECT_EQ(error.rfind("broken.gltf: ", 0), 0u) << error;
  EXPECT_NE(error.find("unexpected end of input"), std::string::npos) << error;  // the problem
  EXPECT_EQ(dropBroken["after"], "carpaint");
  const json& dropGood = report["steps"][2];
  EXPECT_EQ(dropGood["error"], "");
  EXPECT_EQ(dropGood["after"], "good.glb");
}

// A dropped glTF file's emissive rectangles light the page's scene as they light the desktop
// renderer's (glints under area lights, glint_extended_lights.h, in WebGL2): the car paint without
// its punctual lights under two rectangle lights, bit for bit on llvmpipe, and lit by them.
TEST(PageWeb, TheAreaLightsOfADroppedGltfAreTheDesktopRenderersImage) {
  SKIP_WITHOUT_BROWSER();
  scene::Scene lit = scene::makeBuiltinScene("carpaint");
  lit.lights.clear();
  const glm::vec3 centre = 0.5f * (lit.boundsMin() + lit.boundsMax());
  scene::addRectangleLight(lit, glm::vec3(2.0f, 3.0f, 2.0f), centre, 1.5f, 1.0f, glm::vec3(20.0f));
  scene::addRectangleLight(lit, glm::vec3(-2.5f, 2.0f, 2.5f), centre, 1.0f, 1.2f, glm::vec3(15.0f));
  const std::vector<std::byte> glb = scene::encodeGltf(lit, scene::GltfEncoding::Binary);
  const scene::Scene loaded = scene::loadGltf(glb, "lit.glb", "");
  ASSERT_EQ(scene::findAreaLights(loaded).lights.size(), 2u);
  ASSERT_TRUE(loaded.lights.empty());
  constexpr int kSize = 96;
  BrowserJob job("area-lights");
  job.writeFile("lit.glb", glb.data(), glb.size());
  job.steps.push_back({{"kind", "drop"}, {"file", "lit.glb"}, {"output", "lit.rgba"}, {"width", kSize}, {"height", kSize}});
  const json report = job.run("llvmpipe");
  ASSERT_EQ(report["steps"].size(), 1u) << report.dump();
  EXPECT_EQ(report["steps"][0]["error"], "");
  EXPECT_EQ(report["steps"][0]["after"], "lit.glb");
  const std::vector<char> page = job.readFile("lit.rgba");
  ASSERT_EQ(page.size(), static_cast<std::size_t>(kSize) * kSize * 4) << "no frame from the page";
  const ImageRgb8 desktop = desktopImage(loaded, PageView{"lit.glb"}, kSize);
  const ImageDifference d = differenceOf(page, desktop, kSize);
  std::printf("the car paint under two rectangle lights, %dx%d: %d pixels differ from the desktop renderer's, by at most %d/255\n",
              kSize, kSize, d.pixelsDiffering, d.largest);
  EXPECT_EQ(d.pixelsDiffering, 0);
  // Lit by them: the same scene with the rectangles' emission off (no light then) differs.
  scene::Scene unlit = loaded;
  for (scene::Material& material : unlit.materials) material.emissive = glm::vec3(0.0f);
  const ImageRgb8 dark = desktopImage(unlit, PageView{"unlit"}, kSize);
  int litByThem = 0;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const auto& a = desktop.at(x, y);
      const auto& b = dark.at(x, y);
      litByThem += a.r + a.g + a.b > b.r + b.g + b.b + 30;
    }
  }
  std::printf("pixels the rectangle lights brighten by more than 10/255: %d of %d\n", litByThem, kSize * kSize);
  EXPECT_GT(litByThem, kSize * kSize / 10);
}

// The sliders of `glint view` on the page: each one, moved, changes the frame (the sphere: one glint
// material, one light).
TEST(PageWeb, EverySliderChangesTheFrame) {
  SKIP_WITHOUT_BROWSER();
  BrowserJob job("sliders");
  job.steps.push_back({{"kind", "sliders"}, {"name", "sphere"}, {"width", 64}, {"height", 64}});
  const json report = job.run("llvmpipe");
  ASSERT_EQ(report["steps"].size(), 1u) << report.dump();
  const json& changed = report["steps"][0]["changed"];
  EXPECT_EQ(changed.size(), 8u) << changed.dump();  // 5 material sliders, 3 light sliders
  for (const auto& [slider, frameChanged] : changed.items()) EXPECT_TRUE(frameChanged.get<bool>()) << slider;
  EXPECT_EQ(report["steps"][0]["error"], "");
}

}  // namespace
}  // namespace glint
