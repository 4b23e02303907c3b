// `glint extension-schema`: EXT_materials_glint's JSON schema, written from the one table of the
// glint layer's fields (glint/glint_fields.h; docs/cli.md). The repository's schema is its output.
#include <cstddef>
#include <cstdio>
#include <memory>
#include <span>
#include <string>

#include "app/commands.h"
#include "glint/file_io.h"
#include "scene/gltf_glint.h"

namespace glint::app {

void registerExtensionSchemaCommand(CLI::App& app) {
  auto output = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand(
      "extension-schema", "Write EXT_materials_glint's JSON schema from glint's table of the layer's fields");
  command->add_option("-o,--output", *output,
                      "The file (the repository's is extensions/EXT_materials_glint/schema/"
                      "material.EXT_materials_glint.schema.json; default: standard output)");
  command->callback([output] {
    const std::string text = scene::glintExtensionSchema();
    if (output->empty()) {
      std::fputs(text.c_str(), stdout);
      return;
    }
    writeFileAtomically(*output, std::as_bytes(std::span<const char>(text.data(), text.size())));
    std::fprintf(stderr, "glint: wrote %s\n", output->c_str());
  });
}

}  // namespace glint::app
