// CPU benchmarks of the model (docs/benchmarks.md): dictionary generation for the paper's
// configuration, and BRDF evaluations per second of the glint BRDF against Cook-Torrance on the
// same inputs. The ratios are printed from the same run, since the machines are shared and noisy.
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "glint/bsdf.h"
#include "glint/dictionary.h"
#include "glint/pcg.h"

namespace {

using namespace glint;

const Dictionary& dictionary() {
  static const Dictionary d = generateDictionary(DictionaryParameters{});
  return d;
}

struct Query {
  SurfaceFootprint footprint;
  glm::vec3 wo, wi;
};

// Pixel-like queries: uv footprints of 1/1000 of the texture (a 1000-pixel-wide textured object)
// with up to 4:1 anisotropy, view and light directions over the hemisphere, half vectors within
// the specular lobe (where a renderer spends its time; outside it most cells return early).
std::vector<Query> makeQueries(float footprintScale) {
  Pcg32 rng(42, 0);
  auto uniform = [&](float a, float b) { return a + (b - a) * static_cast<float>(rng.nextOpenUnit()); };
  std::vector<Query> queries(4096);
  for (Query& q : queries) {
    q.footprint.uv = glm::vec2(uniform(0, 1), uniform(0, 1));
    q.footprint.duvdx = glm::vec2(footprintScale * uniform(1, 4), 0.0f);
    q.footprint.duvdy = glm::vec2(0.0f, footprintScale);
    const float theta = uniform(0.0f, 1.3f);
    const float phi = uniform(0.0f, 6.283f);
    q.wo = glm::vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    const glm::vec3 m = glm::normalize(glm::vec3(uniform(-0.4f, 0.4f), uniform(-0.4f, 0.4f), 1.0f));
    q.wi = glm::reflect(-q.wo, m);
    if (q.wi.z <= 0.05f) q.wi = glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return queries;
}

void BM_GenerateDictionaryPaperConfiguration(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(generateDictionary(DictionaryParameters{}));
  state.SetLabel("L=16 N=192 R=64 alpha=0.5 s=0.02, all cores");
}
BENCHMARK(BM_GenerateDictionaryPaperConfiguration)->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();

void BM_CookTorrance(benchmark::State& state) {
  const auto queries = makeQueries(1e-3f);
  const CookTorranceBsdf bsdf(glm::vec2(0.5f));
  std::size_t i = 0;
  for (auto _ : state) {
    const Query& q = queries[i++ & 4095];
    benchmark::DoNotOptimize(bsdf.f(q.wo, q.wi));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_CookTorrance);

void glintBenchmark(benchmark::State& state, float logDensity, float footprintScale) {
  const auto queries = makeQueries(footprintScale);
  GlintParameters parameters = defaultGlintParameters();
  parameters.logDensity = logDensity;
  std::vector<GlintBsdf> bsdfs;
  for (const Query& q : queries) bsdfs.emplace_back(dictionary(), parameters, q.footprint);
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 4095;
    benchmark::DoNotOptimize(bsdfs[k].f(queries[k].wo, queries[k].wi));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
// "Default": the 2020 paper's density, 27 (the extension's default is 17, docs/scenes.md).
void BM_GlintDefault(benchmark::State& state) { glintBenchmark(state, 27.0f, 1e-3f); }
void BM_GlintSparse(benchmark::State& state) { glintBenchmark(state, 18.0f, 1e-3f); }
void BM_GlintSmallFootprint(benchmark::State& state) { glintBenchmark(state, 27.0f, 1e-5f); }
BENCHMARK(BM_GlintDefault);
BENCHMARK(BM_GlintSparse);
BENCHMARK(BM_GlintSmallFootprint);

// Importance sampling (docs/sampling.md): samples per second of sample(), each including the
// evaluation of f and pdf at the sampled direction, on the same shading points and view directions
// as above (log density 27 and 18, footprints 1/1000 of the texture). Mixture samples the P-NDF
// (a level, a cell, two marginal CDFs, then the P-NDF at wi); Gaussian samples one Beckmann lobe
// (then the P-NDF at wi for f); Cook-Torrance is the smooth baseline.
std::vector<glm::vec3> sampleUniforms() {
  Pcg32 rng(7, 1);
  std::vector<glm::vec3> u(4096);
  for (glm::vec3& v : u) {
    v = glm::vec3(static_cast<float>(rng.nextOpenUnit()), static_cast<float>(rng.nextOpenUnit()),
                  static_cast<float>(rng.nextOpenUnit()));
  }
  return u;
}

void glintSampleBenchmark(benchmark::State& state, GlintSampler sampler, float logDensity) {
  const auto queries = makeQueries(1e-3f);
  const auto u = sampleUniforms();
  GlintParameters parameters = defaultGlintParameters();
  parameters.logDensity = logDensity;
  std::vector<GlintBsdf> bsdfs;
  for (const Query& q : queries) {
    bsdfs.emplace_back(dictionary(), parameters, q.footprint, Fresnel::none(), Spectrum(1.0f), sampler);
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 4095;
    benchmark::DoNotOptimize(bsdfs[k].sample(queries[k].wo, u[k].x, glm::vec2(u[k].y, u[k].z)));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
void BM_SampleGlintMixture(benchmark::State& state) { glintSampleBenchmark(state, GlintSampler::Mixture, 27.0f); }
void BM_SampleGlintGaussian(benchmark::State& state) { glintSampleBenchmark(state, GlintSampler::Gaussian, 27.0f); }
void BM_SampleGlintMixtureSparse(benchmark::State& state) { glintSampleBenchmark(state, GlintSampler::Mixture, 18.0f); }
void BM_SampleGlintGaussianSparse(benchmark::State& state) {
  glintSampleBenchmark(state, GlintSampler::Gaussian, 18.0f);
}
BENCHMARK(BM_SampleGlintMixture);
BENCHMARK(BM_SampleGlintGaussian);
BENCHMARK(BM_SampleGlintMixtureSparse);
BENCHMARK(BM_SampleGlintGaussianSparse);

void BM_SampleCookTorrance(benchmark::State& state) {
  const auto queries = makeQueries(1e-3f);
  const auto u = sampleUniforms();
  const CookTorranceBsdf bsdf(glm::vec2(0.5f));
  std::size_t i = 0;
  for (auto _ : state) {
    const std::size_t k = i++ & 4095;
    benchmark::DoNotOptimize(bsdf.sample(queries[k].wo, u[k].x, glm::vec2(u[k].y, u[k].z)));
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_SampleCookTorrance);

// Prints every run as usual and keeps the time per iteration, for the ratios.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  RatioReporter() : ConsoleReporter(OO_Tabular) {}  // no colour codes: the output is pasted into docs
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) nanoseconds[run.benchmark_name()] = run.GetAdjustedCPUTime();
  }
  std::map<std::string, double> nanoseconds;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto base = reporter.nanoseconds.find("BM_CookTorrance");
  if (base != reporter.nanoseconds.end()) {
    for (const auto& [name, ns] : reporter.nanoseconds) {
      if (name.rfind("BM_Glint", 0) == 0) std::printf("ratio %s / BM_CookTorrance: %.1fx\n", name.c_str(), ns / base->second);
    }
  }
  benchmark::Shutdown();
  return 0;
}
