#include "test_support.h"

#include "scene/builtin_scenes.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>

#include <gtest/gtest.h>

#include "glint/dictionary_exr.h"
#include "glint/error.h"
#include <tbb/parallel_for.h>

namespace glint::test {

const Dictionary& defaultDictionary() {
  static const Dictionary dictionary = generateDictionary(DictionaryParameters{});
  return dictionary;
}

std::filesystem::path authorsDictionaryFolder() {
  return std::filesystem::path(GLINT_SHARED_DIR) / "reference" / "dict_16_192_64_0p5_0p02";
}

const Dictionary* authorsDictionary() {
  static const std::unique_ptr<Dictionary> dictionary = []() -> std::unique_ptr<Dictionary> {
    if (!std::filesystem::is_directory(authorsDictionaryFolder())) return nullptr;
    return std::make_unique<Dictionary>(loadAuthorsExrDictionary(authorsDictionaryFolder()));
  }();
  return dictionary.get();
}

bool isPaperScaleScene(const std::string& name) { return name == "atrium" || name == "car"; }

std::vector<std::string> smallBuiltinSceneNames() {
  std::vector<std::string> names;
  for (const std::string& name : scene::builtinSceneNames()) {
    if (!isPaperScaleScene(name)) names.push_back(name);
  }
  return names;
}

std::filesystem::path temporaryFolder(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() / ("glint_test_" + std::to_string(::getpid())) / name;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

std::uint32_t crc32Ieee(std::string_view bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char byte : bytes) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

RunResult runGlint(const std::filesystem::path& folder, const std::string& arguments, const std::string& stdinText,
                   const std::string& environment) {
  std::ofstream(folder / "stdin.txt") << stdinText;
  const std::string command = "cd '" + folder.string() + "' && " + environment + " '" GLINT_EXECUTABLE "' " + arguments +
                              " < stdin.txt > stdout.txt 2> stderr.txt";
  const int status = std::system(command.c_str());
  RunResult result;
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(folder / "stdout.txt");
  result.err = slurp(folder / "stderr.txt");
  return result;
}

std::string errorOf(const std::function<void()>& body) {
  try {
    body();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no Error thrown";
  return "";
}

void expectOneLineError(const RunResult& result, const std::string& problem) {
  EXPECT_GT(result.exitCode, 0) << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_NE(result.err.find(problem), std::string::npos) << "expected '" << problem << "' in: " << result.err;
}

float uniform(Pcg32& rng, float low, float high) {
  return low + (high - low) * static_cast<float>(rng.nextOpenUnit());
}

glm::vec2 uniformPair(Pcg32& rng, glm::vec2 low, glm::vec2 high) {
  const float y = uniform(rng, low.y, high.y);
  const float x = uniform(rng, low.x, high.x);
  return {x, y};
}

SurfaceFootprint randomFootprint(Pcg32& rng, float minLength, float maxLength) {
  auto axis = [&] {
    const float length = std::exp(uniform(rng, std::log(minLength), std::log(maxLength)));
    const float angle = uniform(rng, 0.0f, 6.2831853f);
    return glm::vec2(std::cos(angle), std::sin(angle)) * length;
  };
  SurfaceFootprint footprint;
  footprint.uv = uniformPair(rng, glm::vec2(0.0f), glm::vec2(1.0f));
  footprint.duvdx = axis();
  footprint.duvdy = axis();
  return footprint;
}

std::pair<glm::vec2, glm::vec2> turnedDerivatives(float major, float minor, float uvAngle, float screenAngle) {
  const auto turn = [](float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    return glm::mat2(c, s, -s, c);
  };
  const glm::mat2 j = turn(uvAngle) * glm::mat2(major, 0.0f, 0.0f, minor) * turn(screenAngle);
  return {j[0], j[1]};
}

glm::vec3 directionAt(float theta, float phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

glm::vec3 randomDirectionAt(Pcg32& rng, float maxTheta, float maxPhi) {
  const glm::vec2 angles = uniformPair(rng, glm::vec2(0.0f), glm::vec2(maxTheta, maxPhi));
  return directionAt(angles.x, angles.y);
}

double integrateOverSlopes(const std::function<double(glm::vec2)>& integrand, glm::vec2 extent, int cells) {
  const double hx = 2.0 * extent.x / cells;
  const double hy = 2.0 * extent.y / cells;
  // Rows are summed in a fixed order after the parallel part, so the result is deterministic.
  std::vector<double> rows(static_cast<std::size_t>(cells));
  tbb::parallel_for(0, cells, [&](int j) {
    const double y = -extent.y + (j + 0.5) * hy;
    double row = 0.0;
    for (int i = 0; i < cells; ++i) {
      const double x = -extent.x + (i + 0.5) * hx;
      row += integrand(glm::vec2(static_cast<float>(x), static_cast<float>(y)));
    }
    rows[static_cast<std::size_t>(j)] = row;
  });
  double sum = 0.0;
  for (double row : rows) sum += row;
  return sum * hx * hy;
}

double meanNdfOverPositions(const GlintParameters& parameters, glm::vec3 m, int positions, std::uint64_t stream) {
  Pcg32 rng(99, stream);
  double sum = 0.0;
  for (int i = 0; i < positions; ++i) {
    SurfaceFootprint footprint;
    footprint.uv = uniformPair(rng, glm::vec2(0.0f), glm::vec2(1.0f));
    footprint.duvdx = glm::vec2(1e-3f, 0.0f);
    footprint.duvdy = glm::vec2(0.0f, 1e-3f);
    sum += GlintBsdf(defaultDictionary(), parameters, footprint).ndf(m);
  }
  return sum / positions;
}

double integrateOverWholeSlopePlane(const std::function<double(glm::vec2)>& g, glm::vec2 alpha, int cells,
                                    float reach) {
  const float limit = std::asinh(reach);
  return integrateOverSlopes(
      [&](glm::vec2 t) {
        const glm::vec2 slope(alpha.x * std::sinh(t.x), alpha.y * std::sinh(t.y));
        return g(slope) * double(alpha.x) * std::cosh(double(t.x)) * double(alpha.y) * std::cosh(double(t.y));
      },
      glm::vec2(limit), cells);
}

glm::vec2 glintSlopeExtent(const Dictionary& dictionary, glm::vec2 alpha, float rho) {
  const float support = dictionary.parameters().slopeDomain() * std::sqrt(2.0f) / dictionary.parameters().alpha;
  // A correlated cell maps the disc of that radius by M (glintCorrelatedScale): x reaches
  // (sqrt(1 - rho^2) + |rho|) times as far, y as far as without correlation.
  const glm::vec2 shear(std::sqrt(1.0f - rho * rho) + std::abs(rho), 1.0f);
  return glm::max(alpha * support * shear, 4.0f * alpha) * 1.001f;
}

}  // namespace glint::test
