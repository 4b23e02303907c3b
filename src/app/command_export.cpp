// `glint export`: a built-in or loaded scene as a glTF 2.0 file, its glint layers in each
// material's EXT_materials_glint (docs/cli.md, docs/scenes.md "Writing glTF").
#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.h"
#include "app/scene_options.h"
#include "glint/error.h"
#include "scene/gltf_writer.h"

namespace glint::app {

namespace {

struct ExportOptions {
  SceneOptions scene;
  std::string output;
  bool withDefaults = false;
};

void runExport(const ExportOptions& options) {
  const scene::Scene scene = options.scene.loadScene();
  scene::writeGltf(options.output, scene, options.withDefaults);
  std::string losses;
  for (const std::string& loss : scene::gltfLosses(scene)) losses += (losses.empty() ? "" : ", ") + loss;
  std::fprintf(stderr,
               "glint: warning: %s leaves out what glTF cannot hold: %s; glint renders the file under its default "
               "ambient light (--sky brings the procedural sky)\n",
               options.output.c_str(), losses.c_str());
  std::size_t triangles = 0;
  for (const scene::Mesh& mesh : scene.meshes) triangles += mesh.indices.size() / 3;
  const auto count = [](std::size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); };
  std::fprintf(stderr, "glint: wrote %s (%s: %s, %s, %s, %s, %s, %s)\n", options.output.c_str(),
               options.scene.scene.c_str(), count(scene.meshes.size(), "mesh", "meshes").c_str(),
               count(triangles, "triangle", "triangles").c_str(), count(scene.materials.size(), "material", "materials").c_str(),
               count(scene.textures.size(), "texture", "textures").c_str(), count(scene::writtenLights(scene, options.withDefaults).size(), "light", "lights").c_str(),
               count(scene::writtenCameras(scene, options.withDefaults).size(), "camera", "cameras").c_str());
}

}  // namespace

void registerExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* command =
      app.add_subcommand("export", "Write a scene as glTF 2.0 (.glb or .gltf), its glint parameters in EXT_materials_glint");
  options->scene.addSceneAndMaterialsTo(*command);
  command->add_option("-o,--output", options->output, "Output file: .glb (binary) or .gltf (JSON, data embedded)")
      ->required();
  command->add_flag("--with-defaults", options->withDefaults,
                    "Also write what glint made for the scene: the lights it invents for a file without lights and "
                    "the preset cameras (front, side, top, close, default)");
  command->callback([options] { runExport(*options); });
}

}  // namespace glint::app
