#include "glint/specular_model.h"

#include "glint/error.h"

namespace glint {

std::vector<SpecularModel> allSpecularModels() {
  return {SpecularModel::Glint, SpecularModel::CookTorrance, SpecularModel::ZirrKaplanyan,
          SpecularModel::ZirrKaplanyanReference};
}

const char* toString(SpecularModel model) {
  switch (model) {
    case SpecularModel::Glint: return "glint";
    case SpecularModel::CookTorrance: return "cook-torrance";
    case SpecularModel::ZirrKaplanyan: return "zirr-kaplanyan";
    case SpecularModel::ZirrKaplanyanReference: return "zirr-kaplanyan-reference";
  }
  return "unknown";
}

SpecularModel specularModelFromName(const std::string& name) {
  std::string choices;
  for (SpecularModel model : allSpecularModels()) {
    if (name == toString(model)) return model;
    choices += (choices.empty() ? "" : ", ") + std::string(toString(model));
  }
  throw Error("unknown BRDF '" + name + "' (choices: " + choices + ")");
}

}  // namespace glint
