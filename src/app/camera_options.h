// Cameras from the command line (render, view, trace, bench): --look-from, --look-at, --up and --fov
// override the chosen preset's, and --orbit turns it into a turntable sequence (render, trace).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "scene/scene.h"

namespace glint::app {

struct CameraOptions {
  std::vector<float> lookFrom;  // X,Y,Z when given
  std::vector<float> lookAt;
  std::vector<float> up;
  std::optional<float> fov;  // vertical, degrees

  void addTo(CLI::App& command);
  // The preset with what was given in place of its own: position, target, up and vertical field of
  // view (a --fov makes an orthographic preset perspective). Throws Error with one line for a value
  // that makes no camera: not three finite numbers, the eye on its target, up along the view, a
  // field of view outside (0, 180).
  scene::Camera applyTo(const scene::Camera& preset) const;
};

// --orbit N [--orbit-degrees D]: N frames of the camera turned about its up vector through a pivot,
// D / N degrees apart, starting at the camera itself (D = 360 closes the loop without repeating
// the first frame).
struct OrbitOptions {
  std::optional<int> frames;  // none: one frame, no orbit
  std::optional<float> degrees;

  void addTo(CLI::App& command);
  bool enabled() const { return frames.has_value(); }
  // Throws Error with one line for a count outside [1, 100000], degrees not finite or beyond ten
  // turns, or --orbit-degrees without --orbit.
  void validate() const;
  // The cameras of the frames, turned about `pivot`; without --orbit, the camera alone.
  std::vector<scene::Camera> cameras(const scene::Camera& camera, glm::vec3 pivot) const;
  // The image files the frames are written to: `output` alone without --orbit, else its numbered
  // frames (sequenceFramePath) with `extension`.
  std::vector<std::filesystem::path> framePaths(const std::filesystem::path& output, const std::string& extension) const;
};

// The turntable's pivot: --look-at where it was given, the centre of the scene's bounds otherwise.
glm::vec3 orbitPivot(const scene::Scene& scene, const CameraOptions& camera);

// Frame `index` of `count` written for `output`: its stem, a dash and the index with at least four
// digits, then `extension` (render -o turntable.png --orbit 24: turntable-0000.png ...
// turntable-0023.png).
std::filesystem::path sequenceFramePath(const std::filesystem::path& output, int index, int count,
                                        const std::string& extension);

// Whether `output` asks for a video (.mp4).
bool isVideoPath(const std::filesystem::path& output);

// Encodes the PNG frames sequenceFramePath(video, i, count, ".png") into `video` (H.264, 24 frames a
// second) with Debian's ffmpeg, written to a temporary name and renamed. Without ffmpeg on the
// PATH it says so in one line on stderr and returns false: the frames are the output. Throws
// Error with one line when ffmpeg fails.
bool encodeVideo(const std::filesystem::path& video, int count);

}  // namespace glint::app
