// One line of `glint eval` (docs/cli.md): the JSON object's fields, checked, and the BRDF's values.
#include "eval_line.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <set>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "glint/bsdf.h"
#include "glint/error.h"
#include "glint/glint_fields.h"

namespace glint::app {

namespace {

using nlohmann::json;

// The layer's fields `glint eval` takes, named as extras.glint names them (glint_fields.h); the
// others are the shading point's and the BRDF's.
constexpr GlintField kLayerFields[] = {GlintField::Alpha,         GlintField::Rho,
                                       GlintField::LogDensity,    GlintField::RelativeArea,
                                       GlintField::DensityRandomization, GlintField::MaxAnisotropy,
                                       GlintField::PatternSeed,   GlintField::Ndf,
                                       GlintField::Masking,       GlintField::MultipleScattering};
const char* name(GlintField field) { return glintField(field).extras; }

bool isKnownField(const std::string& key) {
  static const std::set<std::string> kPointFields = {"uv", "duvdx", "duvdy", "wo", "wi", "brdf"};
  return kPointFields.contains(key) ||
         std::any_of(std::begin(kLayerFields), std::end(kLayerFields), [&](GlintField f) { return key == name(f); });
}

// An array of N finite numbers, read as T (a float value must be finite as a float).
template <int N, typename T = float>
glm::vec<N, T> readVector(const json& object, const char* field, glm::vec<N, T> fallback) {
  const auto it = object.find(field);
  if (it == object.end()) return fallback;
  if (!it->is_array() || it->size() != N) {
    throw Error(std::string("field '") + field + "' must be an array of " + std::to_string(N) + " numbers");
  }
  glm::vec<N, T> value(T(0));
  for (int i = 0; i < N; ++i) {
    const json& element = (*it)[static_cast<std::size_t>(i)];
    if (!element.is_number()) {
      throw Error(std::string("field '") + field + "' must be an array of " + std::to_string(N) + " numbers");
    }
    value[i] = element.get<T>();
    if (!std::isfinite(value[i])) throw Error(std::string("field '") + field + "' must be finite");
  }
  return value;
}

// A string field, "" when absent.
std::string readString(const json& object, const char* field) {
  const auto it = object.find(field);
  if (it == object.end()) return "";
  if (!it->is_string()) throw Error(std::string("field '") + field + "' must be a string");
  return it->get<std::string>();
}

bool readBool(const json& object, const char* field, bool fallback) {
  const auto it = object.find(field);
  if (it == object.end()) return fallback;
  if (!it->is_boolean()) throw Error(std::string("field '") + field + "' must be true or false");
  return it->get<bool>();
}

float readNumber(const json& object, const char* field, float fallback) {
  const auto it = object.find(field);
  if (it == object.end()) return fallback;
  if (!it->is_number()) throw Error(std::string("field '") + field + "' must be a number");
  const float value = it->get<float>();
  if (!std::isfinite(value)) throw Error(std::string("field '") + field + "' must be finite");
  return value;
}

// A direction at any scale: read in double and divided by its largest component before it is
// normalised, so that neither [1e30, 0, 1e30] (whose squares overflow a float) nor [1e-30, 0, 1e-30]
// (whose squares underflow) loses its direction; only the zero vector has none.
glm::vec3 readDirection(const json& object, const char* field) {
  const glm::dvec3 w = readVector<3, double>(object, field, glm::dvec3(0.0, 0.0, 1.0));
  const double largest = std::max({std::abs(w.x), std::abs(w.y), std::abs(w.z)});
  if (!(largest > 0.0)) throw Error(std::string("field '") + field + "' must be a non-zero direction");
  return glm::vec3(glm::normalize(w / largest));
}

json evaluate(const json& input, const Dictionary& dictionary) {
  if (!input.is_object()) throw Error("expected a JSON object");
  for (const auto& [key, value] : input.items()) {
    if (!isKnownField(key)) throw Error("unknown field '" + key + "'");
  }
  // The layer's fields into the material block, each through its row's member (glint_fields.h),
  // from the model's defaults (the 2020 paper's target, defaultGlintParameters).
  const GlintParameters defaults = defaultGlintParameters();
  kernel::GlintMaterial material = glintDefaultMaterial();
  material.ndf = defaults.ndf;
  material.masking = defaults.masking;
  material.multipleScattering = defaults.multipleScattering ? 1u : 0u;
  for (const GlintField field : kLayerFields) {
    const GlintFieldSpec& spec = glintField(field);
    const char* key = name(field);
    if (!input.contains(key)) continue;
    const std::string quoted = std::string("field '") + key + "'";
    if (const auto* member = std::get_if<float kernel::GlintMaterial::*>(&spec.member)) {
      material.**member = readNumber(input, key, 0.0f);
    } else if (const auto* pair = std::get_if<glm::vec2 kernel::GlintMaterial::*>(&spec.member)) {
      material.**pair = readVector<2>(input, key, glm::vec2(0.0f));
    } else if (const auto* word = std::get_if<kernel::uint kernel::GlintMaterial::*>(&spec.member)) {
      if (spec.kind == GlintFieldKind::Boolean) {
        material.**word = readBool(input, key, false) ? 1u : 0u;
      } else {
        // In double, which holds every 32-bit integer exactly (a float rounds those above 2^24).
        const json& value = input.at(key);
        const double whole = value.is_number() ? value.get<double>() : -1.0;
        if (!(whole >= spec.minimum && whole <= spec.maximum && whole == std::floor(whole))) {
          throw Error(quoted + " must be an integer in [" + std::to_string(static_cast<std::uint64_t>(spec.minimum)) + ", " +
                      std::to_string(static_cast<std::uint64_t>(spec.maximum)) + "]");
        }
        material.**word = static_cast<kernel::uint>(whole);
      }
    } else if (const auto* choice = std::get_if<int kernel::GlintMaterial::*>(&spec.member)) {
      material.**choice = glintChoiceFromName(field, quoted, readString(input, key));
    }
  }
  const GlintParameters parameters = kernel::glintMaterialConstants(material, defaults.footprintPolicy);
  SurfaceFootprint footprint;
  footprint.uv = readVector<2>(input, "uv", footprint.uv);
  footprint.duvdx = readVector<2>(input, "duvdx", footprint.duvdx);
  footprint.duvdy = readVector<2>(input, "duvdy", footprint.duvdy);
  const glm::vec3 wo = readDirection(input, "wo");
  const glm::vec3 wi = readDirection(input, "wi");
  std::string brdf = "glint";
  if (const auto it = input.find("brdf"); it != input.end()) {
    if (!it->is_string()) throw Error("field 'brdf' must be \"glint\" or \"cook-torrance\"");
    brdf = it->get<std::string>();
  }

  // D and P22 at the half vector, when it is above the surface; f is zero where the model is.
  const glm::vec3 sum = wo + wi;
  const glm::vec3 wh = glm::length(sum) > 0.0f ? glm::normalize(sum) : glm::vec3(0.0f);
  // A half vector so near the horizon that its slope overflows a float has P22 = 0, as every
  // distribution's has at infinite slopes; D = P22 / cos^4 is 0 wherever P22 is.
  const glm::vec2 slope = wh.z > 0.0f ? kernel::glintSlopeFromNormal(wh) : glm::vec2(0.0f);
  const bool aboveSurface = wh.z > 0.0f && std::isfinite(slope.x) && std::isfinite(slope.y);
  auto report = [&](const auto& bsdf) {
    const float p22 = aboveSurface ? bsdf.p22(slope) : 0.0f;
    const float d = p22 > 0.0f ? kernel::glintNdfFromP22(p22, wh.z) : 0.0f;
    return json{{"f", bsdf.f(wo, wi).x}, {"D", d}, {"P22", p22}};
  };
  if (brdf == "glint") return report(GlintBsdf(dictionary, parameters, footprint));
  if (brdf == "cook-torrance") {
    validateGlintParameters(parameters);  // the same inputs are accepted by both BRDFs
    validateFootprint(footprint);
    return report(CookTorranceBsdf(parameters.alpha, parameters.rho, Fresnel::none(), Spectrum(1.0f),
                                   microfacetTarget(parameters)));
  }
  throw Error("field 'brdf' must be \"glint\" or \"cook-torrance\", got \"" + brdf + "\"");
}

}  // namespace

std::string evaluateLine(const std::string& line, const Dictionary& dictionary) {
  nlohmann::json input;
  try {
    input = nlohmann::json::parse(line);
  } catch (const nlohmann::json::exception& e) {  // syntax errors, and numbers beyond double's range
    throw Error(std::string("malformed JSON (") + e.what() + ")");
  }
  return evaluate(input, dictionary).dump();
}

}  // namespace glint::app
