// Cameras from the command line (--look-from, --look-at, --up, --fov) and turntable sequences
// (--orbit N, --orbit-degrees D, -o VIDEO.mp4) as a user runs them: `glint render`, `trace` and
// `bench`, and their one-line errors.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "glint/image_io.h"
#include "scene/builtin_scenes.h"
#include "scene/gltf_writer.h"
#include "scene_support.h"
#include "test_support.h"

namespace glint {
namespace {

using namespace glint::test;

// The share of pixels of which a channel differs by more than 0.01 (linear, decoded from the sRGB
// PNGs: a step of 2 to 3 codes in the mid-tones) between two images of the same size.
double differingShare(const std::filesystem::path& a, const std::filesystem::path& b) {
  const ImageRgbF x = readImage(a);
  const ImageRgbF y = readImage(b);
  EXPECT_EQ(x.width, y.width);
  EXPECT_EQ(x.height, y.height);
  if (x.pixels.size() != y.pixels.size()) return 1.0;
  std::size_t differing = 0;
  for (std::size_t k = 0; k < x.pixels.size(); ++k) {
    const glm::vec3 d = glm::abs(x.pixels[k] - y.pixels[k]);
    differing += std::max(d.r, std::max(d.g, d.b)) > 0.01f;
  }
  return static_cast<double>(differing) / static_cast<double>(x.pixels.size());
}

TEST(CameraCli, LookFromAndOrbitPlaceTheSameCamera) {
  // The sphere's default camera turned half a turn about its target is the camera placed by hand
  // at the mirror image of its position across the target's vertical axis (up is +y there).
  const scene::Camera preset = scene::loadScene("sphere").cameras.at("default");
  ASSERT_EQ(preset.up, glm::vec3(0.0f, 1.0f, 0.0f));
  const glm::vec3 p = preset.target;
  const glm::vec3 mirrored(2.0f * p.x - preset.position.x, preset.position.y, 2.0f * p.z - preset.position.z);
  const auto folder = temporaryFolder("camera_orbit");
  const std::string common = "render sphere --size 96x64 --look-at " + triple(p);
  RunResult result = runGlint(folder, common + " -o still.png");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  // Two frames of a whole turn: 0 and 180 degrees.
  result = runGlint(folder, common + " -o turn.png --orbit 2");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("2 frames turn-0000.png .. turn-0001.png"), std::string::npos) << result.err;
  result = runGlint(folder, common + " -o mirrored.png --look-from " + triple(mirrored));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  // The first frame is the still itself, byte for byte.
  EXPECT_EQ(slurp(folder / "turn-0000.png"), slurp(folder / "still.png"));
  // The half turn's position differs from the hand-placed one by float rounding (sin pi is not 0 in
  // float): a glint can cross a cell boundary, so up to 1% of the pixels may differ; the still,
  // seen from the other side, differs in a fifth of them or more.
  EXPECT_LT(differingShare(folder / "turn-0001.png", folder / "mirrored.png"), 0.01);
  EXPECT_GT(differingShare(folder / "still.png", folder / "mirrored.png"), 0.2);
}

TEST(CameraCli, FovAndUpChangeTheView) {
  const auto folder = temporaryFolder("camera_fov");
  const scene::Camera preset = scene::loadScene("sphere").cameras.at("default");
  RunResult result = runGlint(folder, "render sphere --size 64x64 -o preset.png");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  char fov[32];
  std::snprintf(fov, sizeof fov, "%.9g", preset.verticalFovDegrees);
  // The preset's own values leave the image as it is; other values change it.
  result = runGlint(folder, "render sphere --size 64x64 -o same.png --fov " + std::string(fov) + " --up 0,1,0 --look-from " +
                                triple(preset.position) + " --look-at " + triple(preset.target));
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_EQ(slurp(folder / "same.png"), slurp(folder / "preset.png"));
  result = runGlint(folder, "render sphere --size 64x64 -o wide.png --fov 90");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_GT(differingShare(folder / "wide.png", folder / "preset.png"), 0.2);
  result = runGlint(folder, "render sphere --size 64x64 -o rolled.png --up 1,0,0");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_GT(differingShare(folder / "rolled.png", folder / "preset.png"), 0.2);
}

TEST(CameraCli, FlagsReproduceAGltfCameraExactly) {
  // A glTF file's camera, rolled (its up is not +y) and with its own field of view: the values the
  // loader reads from its node and projection, given as --look-from, --look-at, --up and --fov,
  // render the image of --camera NAME byte for byte, in both renderers.
  const auto folder = temporaryFolder("camera_gltf");
  scene::Scene written = texturedTestScene();
  scene::Camera tilted;
  tilted.position = {1.3f, 0.9f, 2.2f};
  tilted.target = {-0.1f, 0.35f, 0.05f};
  tilted.up = glm::normalize(glm::vec3(0.3f, 1.0f, -0.1f));
  tilted.verticalFovDegrees = 33.0f;
  written.cameras["tilted"] = tilted;
  scene::writeGltf(folder / "scene.glb", written);
  const scene::Camera loaded = scene::loadScene((folder / "scene.glb").string()).cameras.at("tilted");
  ASSERT_GT(std::abs(loaded.up.x), 0.1f);  // the roll survived the file
  char fov[32];
  std::snprintf(fov, sizeof fov, "%.9g", loaded.verticalFovDegrees);
  const std::string flags = " --look-from " + triple(loaded.position) + " --look-at " + triple(loaded.target) +
                            " --up " + triple(loaded.up) + " --fov " + fov;
  for (const std::string command : {"render scene.glb --size 64x48", "trace scene.glb --size 24x16 --spp 2"}) {
    const std::string extension = command.rfind("render", 0) == 0 ? ".png" : ".exr";
    RunResult result = runGlint(folder, command + " --camera tilted -o named" + extension);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    result = runGlint(folder, command + flags + " -o flags" + extension);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    result = runGlint(folder, command + " -o preset" + extension);
    ASSERT_EQ(result.exitCode, 0) << result.err;
    EXPECT_EQ(slurp(folder / ("flags" + extension)), slurp(folder / ("named" + extension))) << command;
    EXPECT_NE(slurp(folder / ("preset" + extension)), slurp(folder / ("named" + extension))) << command;
  }
}

TEST(CameraCli, AnOrbitOfEightFramesIsTheSameOnEveryRun) {
  // Two runs of --orbit 8 into two folders: eight numbered frames each (no ninth), byte for byte the
  // same, and each frame a different view.
  for (const std::string command : {"render sphere --size 40x32 -o spin.png", "trace sphere --size 16x12 --spp 2 -o spin.exr"}) {
    const std::string extension = command.substr(command.size() - 4);
    std::vector<std::string> runs[2];
    for (int run = 0; run < 2; ++run) {
      const auto folder = temporaryFolder("camera_orbit8_" + std::to_string(run));
      const RunResult result = runGlint(folder, command + " --orbit 8");
      ASSERT_EQ(result.exitCode, 0) << result.err;
      for (int frame = 0; frame < 8; ++frame) {
        char name[32];
        std::snprintf(name, sizeof name, "spin-%04d%s", frame, extension.c_str());
        ASSERT_TRUE(std::filesystem::exists(folder / name)) << command << ": " << name;
        runs[run].push_back(slurp(folder / name));
      }
      EXPECT_FALSE(std::filesystem::exists(folder / ("spin-0008" + extension))) << command;
      EXPECT_FALSE(std::filesystem::exists(folder / ("spin" + extension))) << command;
    }
    for (int frame = 0; frame < 8; ++frame) {
      EXPECT_EQ(runs[0][frame], runs[1][frame]) << command << ", frame " << frame;
      if (frame > 0) EXPECT_NE(runs[0][frame], runs[0][frame - 1]) << command << ", frame " << frame;
    }
  }
}

TEST(CameraCli, BadCamerasAndSequencesAreOneLineErrors) {
  const auto folder = temporaryFolder("camera_errors");
  const std::pair<std::string, std::string> cases[] = {
      {"--look-from 1,2", "--look-from takes three finite numbers"},
      {"--look-at 1,nan,2", "--look-at takes three finite numbers"},
      {"--up 0,0,0", "--up must not be zero"},
      {"--look-from 0,0,3 --look-at 0,0,3", "position and look-at point are the same"},
      {"--look-from 0,2,0 --look-at 0,0,0 --up 0,1,0", "up vector is along its view direction"},
      {"--fov 0", "--fov must be in (0, 180)"},
      {"--fov -30", "--fov must be in (0, 180)"},
      {"--fov 180", "--fov must be in (0, 180)"},
      {"--orbit 0", "--orbit must be in [1, 100000]"},
      {"--orbit -8", "--orbit must be in [1, 100000]"},
      {"--orbit-degrees 90", "--orbit-degrees needs --orbit N"},
      {"--orbit 3 --orbit-degrees inf", "--orbit-degrees must be a number"},
  };
  for (const auto& [arguments, problem] : cases) {
    const RunResult result = runGlint(folder, "render sphere --size 32x32 -o out.png " + arguments);
    expectOneLineError(result, problem);
    EXPECT_FALSE(std::filesystem::exists(folder / "out.png")) << arguments;
    EXPECT_FALSE(std::filesystem::exists(folder / "out-0000.png")) << arguments;
  }
  // The same for the path tracer, which writes an EXR and a PNG per frame.
  for (const auto& [arguments, problem] : {std::pair<std::string, std::string>{"--fov -30", "--fov must be in (0, 180)"},
                                           {"--look-from 1,1,1 --look-at 1,1,1", "position and look-at point are the same"},
                                           {"--orbit -8", "--orbit must be in [1, 100000]"},
                                           {"--orbit 0", "--orbit must be in [1, 100000]"}}) {
    expectOneLineError(runGlint(folder, "trace sphere --size 8x8 --spp 1 -o out.exr " + arguments), problem);
    for (const char* file : {"out.exr", "out.png", "out-0000.exr", "out-0000.png"}) {
      EXPECT_FALSE(std::filesystem::exists(folder / file)) << arguments << ": " << file;
    }
  }
  expectOneLineError(runGlint(folder, "render sphere --size 32x32 -o out.mp4"), "out.mp4: a video (.mp4) needs --orbit N");
  expectOneLineError(runGlint(folder, "trace sphere --size 32x32 -o out.mp4"), "out.mp4: a video (.mp4) needs --orbit N");
  expectOneLineError(runGlint(folder, "bench sphere --size 32x32 --frames 1 --fov 200"), "--fov must be in (0, 180)");
  EXPECT_TRUE(std::filesystem::is_empty(folder / "") || !std::filesystem::exists(folder / "out.mp4"));
}

// A camera too far out for its float arithmetic is refused as such, not as an up vector along the
// view (the view's length overflowed).
TEST(CameraCli, CoordinatesBeyondTheCamerasRangeAreRefused) {
  const auto folder = temporaryFolder("camera_range");
  expectOneLineError(runGlint(folder, "render sphere --size 16x16 -o out.png --look-from 1e30,0,0"),
                     "--look-from takes numbers within +-1e9");
  expectOneLineError(runGlint(folder, "trace sphere --size 8x8 --spp 1 -o out.exr --look-at 1e38,1e38,1e38"),
                     "--look-at takes numbers within +-1e9");
  for (const char* file : {"out.png", "out.exr"}) EXPECT_FALSE(std::filesystem::exists(folder / file)) << file;
}

// An orbit's frames are one output: a frame that cannot be written (a folder in its place) leaves
// none of the frames before it, for the rasteriser and for the path tracer (its EXRs and PNGs).
// Such a frame is now refused before the render (OutputsWithoutAPlaceAreRefusedFirst); a failure
// that only the write meets (a full disk) leaves none either, as the frames are staged
// (ImageIoWrite.StagedFilesAppearTogetherOrNotAtAll).
TEST(CameraCli, AnOrbitThatFailsLeavesNoFrame) {
  const auto folder = temporaryFolder("camera_orbit_failure");
  std::filesystem::create_directory(folder / "spin-0002.png");
  expectOneLineError(runGlint(folder, "render sphere --size 16x16 --orbit 4 -o spin.png"),
                     "spin-0002.png: cannot write (is a directory)");
  std::filesystem::create_directory(folder / "walk-0002.exr");
  expectOneLineError(runGlint(folder, "trace sphere --size 8x8 --spp 1 --orbit 3 -o walk.exr"),
                     "walk-0002.exr: cannot write (is a directory)");
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if (name.find("-00") != std::string::npos || name.find(".tmp") != std::string::npos) left.push_back(name);
  }
  std::sort(left.begin(), left.end());
  EXPECT_EQ(left, (std::vector<std::string>{"spin-0002.png", "walk-0002.exr"}));
}

// An output without a place (a missing folder, a folder in a file's place, a preview's or a later
// frame's) is refused before anything is loaded or rendered: here before a dictionary that does not
// exist is read, which would otherwise be the error.
TEST(CameraCli, OutputsWithoutAPlaceAreRefusedFirst) {
  const auto folder = temporaryFolder("camera_output_place");
  std::filesystem::create_directory(folder / "p.png");
  std::filesystem::create_directory(folder / "spin-0002.png");
  const std::string dictionary = " --dict missing.gdict";
  expectOneLineError(runGlint(folder, "trace sphere --size 8x8 --spp 1 -o nodir/a.exr" + dictionary),
                     "nodir/a.exr: cannot create (No such file or directory)");
  expectOneLineError(runGlint(folder, "trace sphere --size 8x8 --spp 1 -o p.exr" + dictionary), "p.png: cannot write (is a directory)");
  expectOneLineError(runGlint(folder, "render sphere --size 8x8 --orbit 4 -o spin.png" + dictionary),
                     "spin-0002.png: cannot write (is a directory)");
  expectOneLineError(runGlint(folder, "render sphere --size 8x8 -o nodir/r.png" + dictionary),
                     "nodir/r.png: cannot create (No such file or directory)");
  std::filesystem::create_directory(folder / "turn.mp4");
  expectOneLineError(runGlint(folder, "trace sphere --size 8x8 --spp 1 --orbit 2 -o turn.mp4" + dictionary),
                     "turn.mp4: cannot write (is a directory)");
  EXPECT_FALSE(std::filesystem::exists(folder / "p.exr"));
  EXPECT_FALSE(std::filesystem::exists(folder / "spin-0000.png"));
}

TEST(CameraCli, AVideoWithoutFfmpegLeavesTheFramesAndSaysSo) {
  const auto folder = temporaryFolder("camera_video_absent");
  // A PATH without ffmpeg (the shell and glint are found by their full paths).
  const RunResult result = runGlint(folder, "render sphere --size 32x32 --orbit 3 -o spin.mp4", "", "PATH=/nonexistent");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("ffmpeg was not found, so spin.mp4 was not made: the frames are the output"),
            std::string::npos)
      << result.err;
  for (const char* frame : {"spin-0000.png", "spin-0001.png", "spin-0002.png"}) {
    EXPECT_TRUE(std::filesystem::exists(folder / frame)) << frame;
  }
  EXPECT_FALSE(std::filesystem::exists(folder / "spin.mp4"));
}

TEST(CameraCli, AVideoWithFfmpeg) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) GTEST_SKIP() << "ffmpeg is not installed (apt-get install ffmpeg)";
  const auto folder = temporaryFolder("camera_video");
  const RunResult result = runGlint(folder, "render sphere --size 33x31 --orbit 4 --orbit-degrees 90 -o spin.mp4");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  EXPECT_NE(result.err.find("wrote spin.mp4"), std::string::npos) << result.err;
  const std::string video = slurp(folder / "spin.mp4");
  ASSERT_GT(video.size(), 8u);
  EXPECT_EQ(video.substr(4, 4), "ftyp");  // an MP4 file's first box
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(CameraCli, TraceWritesNumberedFramesAndBenchTakesTheCamera) {
  const auto folder = temporaryFolder("camera_trace");
  RunResult result = runGlint(folder, "trace sphere --size 16x16 --spp 1 --orbit 2 -o t.exr");
  ASSERT_EQ(result.exitCode, 0) << result.err;
  for (const char* file : {"t-0000.exr", "t-0000.png", "t-0001.exr", "t-0001.png"}) {
    EXPECT_TRUE(std::filesystem::exists(folder / file)) << file;
  }
  EXPECT_FALSE(std::filesystem::exists(folder / "t.exr"));
  // The two frames see the sphere from opposite sides.
  EXPECT_NE(slurp(folder / "t-0000.png"), slurp(folder / "t-0001.png"));
  result = runGlint(folder, "bench sphere --size 16x16 --frames 1 --warmup 0 --fov 30 --look-from 0,1,4");
  EXPECT_EQ(result.exitCode, 0) << result.err;
}

}  // namespace
}  // namespace glint
