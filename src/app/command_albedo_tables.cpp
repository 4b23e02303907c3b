// `glint albedo-tables`: computes the directional-albedo tables of the multiple-scattering
// compensation and writes them as the kernel header the CPU and GLSL read (docs/cli.md;
// docs/method.md, "Multiple scattering").
#include <cstddef>
#include <cstdio>
#include <memory>
#include <span>
#include <string>

#include "glint/albedo_table_generator.h"
#include "commands.h"
#include "glint/file_io.h"

namespace glint::app {

void registerAlbedoTablesCommand(CLI::App& app) {
  auto output = std::make_shared<std::string>();
  CLI::App* command = app.add_subcommand(
      "albedo-tables", "Compute the multiple-scattering albedo tables and write them as a kernel header");
  command->add_option("-o,--output", *output, "The header to write (the repository's is src/glint/kernel/albedo_tables.h)")
      ->required();
  command->callback([output] {
    const std::string text = albedoTablesHeader(computeAlbedoTables());
    writeFileAtomically(*output, std::as_bytes(std::span<const char>(text.data(), text.size())));
    std::fprintf(stderr, "glint: wrote %s\n", output->c_str());
  });
}

}  // namespace glint::app
