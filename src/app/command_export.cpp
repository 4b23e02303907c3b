// `glint export`: a built-in or loaded scene as a glTF 2.0 file, its glint layers in each
// material's EXT_materials_glint (docs/cli.md, docs/scenes.md "Writing glTF").
#include <cstdio>
#include <memory>

#include "app/commands.h"
#include "app/scene_options.h"
#include "glint/error.h"
#include "scene/gltf_writer.h"

namespace glint::app {

namespace {

struct ExportOptions {
  SceneOptions scene;
  std::string output;
};

void runExport(const ExportOptions& options) {
  const scene::Scene scene = options.scene.loadScene();
  scene::writeGltf(options.output, scene);
  std::string losses;
  for (const std::string& loss : scene::gltfLosses(scene)) losses += (losses.empty() ? "" : ", ") + loss;
  std::fprintf(stderr,
               "glint: warning: %s leaves out what glTF cannot hold: %s; glint renders the file under its default "
               "ambient light (--sky brings the procedural sky)\n",
               options.output.c_str(), losses.c_str());
  std::size_t triangles = 0;
  for (const scene::Mesh& mesh : scene.meshes) triangles += mesh.indices.size() / 3;
  std::fprintf(stderr, "glint: wrote %s (%s: %zu meshes, %zu triangles, %zu materials, %zu textures, %zu lights, %zu cameras)\n",
               options.output.c_str(), options.scene.scene.c_str(), scene.meshes.size(), triangles,
               scene.materials.size(), scene.textures.size(), scene.lights.size(), scene.cameras.size());
}

}  // namespace

void registerExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command =
      app.add_subcommand("export", "Write a scene as glTF 2.0 (.glb or .gltf), its glint parameters in EXT_materials_glint");
  options->scene.addSceneAndMaterialsTo(*command);
  command->add_option("-o,--output", options->output, "Output file: .glb (binary) or .gltf (JSON, data embedded)")
      ->required();
  command->callback([options] { runExport(*options); });
}

}  // namespace glint::app
