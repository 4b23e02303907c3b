#include "scene/gltf_glint.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <utility>
#include <variant>

#include "glint/error.h"
#include "scene/gltf_field_types.h"

namespace glint::scene {

namespace {

using nlohmann::json;

// Every glTF object may carry these two (glTF 2.0's glTFProperty): the extension's object and its
// textureInfo objects accept them, and glint ignores what they hold.
constexpr std::array<const char*, 2> kPropertyMembers = {"extensions", "extras"};

// The fields of one glint object, named as its form spells them.
class Reader {
 public:
  Reader(const json& fields, GlintSpelling spelling) : fields_(fields), spelling_(spelling) {}

  const char* name(GlintField field) const { return glintFieldName(field, spelling_); }
  bool has(GlintField field) const { return fields_.contains(name(field)); }
  const json& at(GlintField field) const { return fields_.at(name(field)); }

  // An unknown member is an error, so that a misspelt name is not silently ignored.
  void refuseUnknown(std::span<const GlintField> known, bool propertyMembers) const {
    for (const auto& item : fields_.items()) {
      const std::string& key = item.key();
      const bool isKnown =
          std::any_of(known.begin(), known.end(), [&](GlintField f) { return key == name(f); }) ||
          (propertyMembers && std::find(kPropertyMembers.begin(), kPropertyMembers.end(), key) != kPropertyMembers.end());
      if (!isKnown) {
        std::string list;
        for (GlintField f : known) list += (list.empty() ? "" : ", ") + std::string(name(f));
        throw Error("unknown field '" + shown(key) + "' (known: " + list + ")");
      }
    }
  }

 private:
  // A member name as a message shows it: control characters as '?', so that the message stays one
  // harmless line.
  static std::string shown(std::string key) {
    for (char& c : key) {
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    }
    return key;
  }

  const json& fields_;
  GlintSpelling spelling_;
};

float numberField(const json& value, const std::string& field) {
  if (!value.is_number()) throw Error(field + " must be a number, got " + describeJsonValue(value));
  // Compared in double: a double beyond the largest float has no float to convert to.
  const double number = value.get<double>();
  if (!(std::abs(number) <= std::numeric_limits<float>::max())) {
    throw Error(field + " " + describeJsonValue(value) + " is beyond a float's range");
  }
  return static_cast<float>(number);
}

// true or false; also 0 or 1, which tools that keep booleans as numbers write back (Blender 3.4
// re-exports custom properties so).
bool booleanField(const json& value, const std::string& field) {
  if (value.is_boolean()) return value.get<bool>();
  if (value.is_number() && (value.get<double>() == 0.0 || value.get<double>() == 1.0)) return value.get<double>() == 1.0;
  throw Error(field + " must be true or false (or 0 or 1), got " + describeJsonValue(value));
}

// An integer in [low, high]; a number with a fractional part, or out of range, is an error.
std::uint64_t wholeField(const json& value, const std::string& field, std::uint64_t low, std::uint64_t high) {
  bool ok = false;
  std::uint64_t result = 0;
  if (value.is_number_unsigned()) {
    result = value.get<std::uint64_t>();
    ok = true;
  } else if (value.is_number_integer()) {
    ok = value.get<std::int64_t>() >= 0;
    result = ok ? static_cast<std::uint64_t>(value.get<std::int64_t>()) : 0;
  } else if (value.is_number_float()) {
    const double number = value.get<double>();
    ok = number >= 0.0 && number == std::floor(number) && number <= static_cast<double>(high);
    result = ok ? static_cast<std::uint64_t>(number) : 0;
  }
  if (!ok || result < low || result > high) {
    throw Error(field + " must be an integer in [" + std::to_string(low) + ", " + std::to_string(high) + "], got " +
                describeJsonValue(value));
  }
  return result;
}

glm::vec2 pairField(const json& value, const std::string& field) {
  if (!value.is_array() || value.size() != 2) throw Error(field + " must be an array of two numbers");
  return {numberField(value[0], field + "[0]"), numberField(value[1], field + "[1]")};
}

// Checks the value `set` gives a field against the kernel's range for it: validateGlintLayer on a
// layer that is valid but for that value, its message from " must" on given the file's name for
// the field ("relativeArea must be in (0, 1], got 2").
void checkRange(const std::string& field, const std::function<void(GlintLayer&)>& set) {
  GlintLayer probe;
  probe.enabled = true;
  set(probe);
  try {
    validateGlintLayer(probe, 0);
  } catch (const Error& e) {
    const std::string message = e.what();
    const std::size_t must = message.find(" must ");
    throw Error(field + (must == std::string::npos ? ": " + message : message.substr(must)));
  }
}

// A texture reference: a glTF textureInfo object in the extension ({"index": 2}, with texCoord,
// extensions and extras allowed), a texture index in extras.glint. Returns the scene texture.
int textureField(const json& value, GlintSpelling spelling, const std::string& field, const GlintTextureSource& textures) {
  const json* index = &value;
  std::string indexName = field;
  if (spelling == GlintSpelling::Extension) {
    if (!value.is_object() || !value.contains("index")) {
      throw Error(field + " must be a textureInfo object with an index, got " + describeJsonValue(value));
    }
    for (const auto& item : value.items()) {
      const std::string& key = item.key();
      if (key != "index" && key != "texCoord" && std::find(kPropertyMembers.begin(), kPropertyMembers.end(), key) == kPropertyMembers.end()) {
        throw Error(field + ": unknown textureInfo member (known: index, texCoord, extensions, extras)");
      }
    }
    index = &value["index"];
    indexName = field + ".index";
    if (value.contains("texCoord")) {
      const std::uint64_t texCoord = wholeField(value["texCoord"], field + ".texCoord", 0, 0x7fffffff);
      if (texCoord != 0) textures.noteUnread("textures on a texCoord other than 0 are mapped with TEXCOORD_0", field);
    }
    if (value.contains("extensions")) {
      const json& extensions = value["extensions"];
      if (!extensions.is_object()) throw Error(field + ".extensions must be an object, got " + describeJsonValue(extensions));
      if (extensions.contains("KHR_texture_transform")) {
        textures.noteUnread("KHR_texture_transform is not applied to glint textures, which are mapped with TEXCOORD_0", field);
      }
    }
  }
  if (textures.textureCount == 0) throw Error(field + ": the file has no textures");
  const auto gltfIndex = static_cast<int>(wholeField(*index, indexName, 0, textures.textureCount - 1));
  try {
    return textures.sceneTexture(gltfIndex);
  } catch (const Error& e) {
    throw Error(field + ": " + e.what());
  }
}

MicrofacetTarget readTarget(const Reader& reader, MicrofacetTarget target) {
  if (reader.has(GlintField::Ndf)) {
    const json& ndf = reader.at(GlintField::Ndf);
    if (!ndf.is_string()) {
      throw Error(std::string(reader.name(GlintField::Ndf)) + " must be " + glintChoiceList(GlintField::Ndf));
    }
    target.ndf = ndfFromName(reader.name(GlintField::Ndf), ndf.get<std::string>());
  }
  if (reader.has(GlintField::Masking)) {
    const json& masking = reader.at(GlintField::Masking);
    if (!masking.is_string()) {
      throw Error(std::string(reader.name(GlintField::Masking)) + " must be " + glintChoiceList(GlintField::Masking));
    }
    target.masking = maskingFromName(reader.name(GlintField::Masking), masking.get<std::string>());
  }
  if (reader.has(GlintField::MultipleScattering)) {
    target.multipleScattering =
        booleanField(reader.at(GlintField::MultipleScattering), reader.name(GlintField::MultipleScattering));
  }
  return target;
}

}  // namespace

const char* glintFieldName(GlintField field, GlintSpelling spelling) {
  return spelling == GlintSpelling::Extension ? glintField(field).extension : glintField(field).extras;
}

GltfGlint readGlintLayer(const json& fields, GlintSpelling spelling, float roughness, MicrofacetTarget specular,
                         const GlintTextureSource& textures) {
  if (!fields.is_object()) throw Error("must be an object, got " + describeJsonValue(fields));
  const Reader reader(fields, spelling);
  std::array<GlintField, kGlintFieldCount> every{};
  for (std::size_t i = 0; i < kGlintFieldCount; ++i) every[i] = kGlintFields[i].field;
  // glTF properties may carry extensions and extras; extras.glint is itself inside extras.
  reader.refuseUnknown(every, spelling == GlintSpelling::Extension);

  GltfGlint result;
  result.specular = readTarget(reader, specular);
  GlintLayer& layer = result.layer;
  layer.enabled = true;
  layer.alpha = glm::vec2(alphaFromRoughness(roughness));
  if (reader.has(GlintField::Alpha)) {
    const json& alpha = reader.at(GlintField::Alpha);
    const std::string name = reader.name(GlintField::Alpha);
    // extras.glint takes one number for an isotropic layer; the extension always two.
    if (spelling == GlintSpelling::Extras && alpha.is_number()) {
      layer.alpha = glm::vec2(numberField(alpha, name));
      checkRange(name, [&](GlintLayer& probe) { probe.alpha = layer.alpha; });
    } else if (alpha.is_array()) {
      layer.alpha = pairField(alpha, name);
      for (int k = 0; k < 2; ++k) {
        checkRange(name + "[" + std::to_string(k) + "]", [&](GlintLayer& probe) { probe.alpha = glm::vec2(layer.alpha[k]); });
      }
    } else {
      throw Error(name + (spelling == GlintSpelling::Extras ? " must be a number or an array of two numbers"
                                                           : " must be an array of two numbers"));
    }
  }
  // Every other field of the block, through its row's member: the specular target's fields went
  // to `result.specular` above, alpha has its own rule, textures follow.
  for (const GlintFieldSpec& spec : kGlintFields) {
    const GlintField field = spec.field;
    if (field == GlintField::Alpha || !reader.has(field) || isSpecularTargetField(field)) {
      continue;
    }
    const json& value = reader.at(field);
    const std::string name = reader.name(field);
    if (const auto* member = std::get_if<float kernel::GlintMaterial::*>(&spec.member)) {
      const float number = numberField(value, name);
      const auto pointer = *member;  // a named variable: lambdas cannot capture bindings in clang 14
      try {
        checkRange(name, [&](GlintLayer& probe) { probe.*pointer = number; });
      } catch (const Error& e) {
        // A number no float holds but 0 (relativeArea 1e-46) is refused as 0: said why it is 0.
        if (number == 0.0f && value.get<double>() != 0.0) {
          throw Error(name + " " + describeJsonValue(value) + " is too small for a 32-bit float and would be 0: " + e.what());
        }
        throw;
      }
      layer.*pointer = number;
    } else if (const auto* pair = std::get_if<glm::vec2 kernel::GlintMaterial::*>(&spec.member)) {
      const glm::vec2 numbers = pairField(value, name);
      const auto pointer = *pair;
      for (int k = 0; k < 2; ++k) {
        checkRange(name + "[" + std::to_string(k) + "]", [&](GlintLayer& probe) { (probe.*pointer)[k] = numbers[k]; });
      }
      layer.*pointer = numbers;
    } else if (const auto* word = std::get_if<kernel::uint kernel::GlintMaterial::*>(&spec.member)) {
      layer.**word = spec.kind == GlintFieldKind::Boolean
                         ? (booleanField(value, name) ? 1u : 0u)
                         : static_cast<kernel::uint>(wholeField(value, name, static_cast<std::uint64_t>(spec.minimum),
                                                                static_cast<std::uint64_t>(spec.maximum)));
    } else if (const auto* choice = std::get_if<int kernel::GlintMaterial::*>(&spec.member)) {
      if (!value.is_string()) throw Error(name + " must be " + glintChoiceList(field));
      layer.**choice = glintChoiceFromName(field, name, value.get<std::string>());
    }
  }
  const std::pair<GlintField, int GlintLayer::*> textureFields[] = {
      {GlintField::RoughnessTexture, &GlintLayer::roughnessTexture},
      {GlintField::LogDensityTexture, &GlintLayer::logDensityTexture},
      {GlintField::RelativeAreaTexture, &GlintLayer::relativeAreaTexture}};
  for (const auto& [field, member] : textureFields) {
    if (reader.has(field)) layer.*member = textureField(reader.at(field), spelling, reader.name(field), textures);
  }
  return result;
}

MicrofacetTarget readGlintSpecularTarget(const json& fields, MicrofacetTarget specular) {
  if (!fields.is_object()) throw Error("must be an object, got " + describeJsonValue(fields));
  const Reader reader(fields, GlintSpelling::Extras);
  reader.refuseUnknown(kSpecularTargetFields, false);
  return readTarget(reader, specular);
}

namespace {

// The schema's JSON as glTF's schemas lay it out: four spaces an indent, an object's members one a
// line, arrays (and the objects inside them) on one line.
void writeSchemaJson(const nlohmann::ordered_json& value, int depth, bool inline_, std::string& out) {
  if (value.is_object()) {
    if (value.empty()) {
      out += "{ }";
      return;
    }
    const std::string indent(static_cast<std::size_t>(4 * (depth + 1)), ' ');
    out += inline_ ? "{ " : "{\n";
    bool first = true;
    for (const auto& [key, member] : value.items()) {
      if (!first) out += inline_ ? ", " : ",\n";
      first = false;
      if (!inline_) out += indent;
      out += nlohmann::ordered_json(key).dump();
      out += ": ";
      writeSchemaJson(member, depth + 1, inline_ || member.is_array(), out);
    }
    if (inline_) {
      out += " }";
    } else {
      out += '\n';
      out.append(static_cast<std::size_t>(4 * depth), ' ');
      out += '}';
    }
  } else if (value.is_array()) {
    out += "[ ";
    for (std::size_t i = 0; i < value.size(); ++i) {
      if (i > 0) out += ", ";
      writeSchemaJson(value[i], depth, true, out);
    }
    out += " ]";
  } else if (value.is_number_float()) {
    // The shortest decimal that reads back as the double, with a point or an exponent (2.0, 0.005,
    // 1.401298464324817e-45).
    char text[32];
    const auto written = std::to_chars(text, text + sizeof text, value.get<double>());
    std::string number(text, written.ptr);
    if (number.find_first_of(".e") == std::string::npos) number += ".0";
    out += number;
  } else {
    out += value.dump();
  }
}

// A value of a field as the schema writes it: a whole number for integers, a float otherwise.
nlohmann::ordered_json schemaNumber(const GlintFieldSpec& spec, double value) {
  if (spec.kind == GlintFieldKind::Integer) return static_cast<std::uint64_t>(value);
  return value;
}

nlohmann::ordered_json fieldSchema(const GlintFieldSpec& spec) {
  using ordered = nlohmann::ordered_json;
  ordered field = ordered::object();
  auto range = [&](ordered& into) {
    into[spec.exclusiveMinimum ? "exclusiveMinimum" : "minimum"] = schemaNumber(spec, spec.minimum);
    into["maximum"] = schemaNumber(spec, spec.maximum);
  };
  switch (spec.kind) {
    case GlintFieldKind::Choice: {
      field["type"] = "string";
      ordered names = ordered::array();
      for (const char* name : spec.choices) {
        if (name != nullptr) names.push_back(name);
      }
      field["enum"] = names;
      field["description"] = spec.meaning;
      field["default"] = glintChoiceName(spec.field, static_cast<int>(spec.defaultValue));
      break;
    }
    case GlintFieldKind::Boolean:
      field["type"] = "boolean";
      field["description"] = spec.meaning;
      field["default"] = spec.defaultValue != 0.0;
      break;
    case GlintFieldKind::Number:
    case GlintFieldKind::Integer:
      field["type"] = spec.kind == GlintFieldKind::Integer ? "integer" : "number";
      field["description"] = spec.meaning;
      if (spec.hasDefault) field["default"] = schemaNumber(spec, spec.defaultValue);
      range(field);
      break;
    case GlintFieldKind::Pair: {
      field["type"] = "array";
      field["description"] = spec.meaning;
      ordered items = ordered::object();
      items["type"] = "number";
      range(items);
      field["items"] = items;
      field["minItems"] = 2;
      field["maxItems"] = 2;
      if (spec.hasDefault) field["default"] = ordered::array({spec.defaultValue, spec.defaultSecond});
      break;
    }
    case GlintFieldKind::Texture:
      field["allOf"] = ordered::array({ordered::object({{"$ref", "textureInfo.schema.json"}})});
      field["description"] = spec.meaning;
      break;
  }
  return field;
}

}  // namespace

std::string glintExtensionSchema() {
  using ordered = nlohmann::ordered_json;
  ordered schema = ordered::object();
  schema["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  schema["$id"] = std::string("material.") + kGlintExtensionName + ".schema.json";
  schema["title"] = std::string(kGlintExtensionName) + " glTF Material Extension";
  schema["type"] = "object";
  schema["description"] =
      "glTF extension that gives a material's specular lobe a procedural glint microstructure: discrete microfacets "
      "that sparkle up close and average to a smooth microfacet lobe from afar.";
  schema["allOf"] = ordered::array({ordered::object({{"$ref", "glTFProperty.schema.json"}})});
  ordered properties = ordered::object();
  for (const GlintFieldSpec& spec : kGlintFields) properties[spec.extension] = fieldSchema(spec);
  for (const char* member : kPropertyMembers) properties[member] = ordered::object();
  schema["properties"] = properties;
  schema["additionalProperties"] = false;
  std::string out;
  writeSchemaJson(schema, 0, false, out);
  return out + "\n";
}

}  // namespace glint::scene
