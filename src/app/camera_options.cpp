#include "app/camera_options.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <sstream>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "glint/error.h"
#include "glint/image_io.h"
#include "scene/camera_moves.h"

extern char** environ;

namespace glint::app {

namespace {

// Coordinates beyond this would overflow the camera's float arithmetic (the view vector's length
// squares them) and leave its frame undefined.
constexpr float kLargestCoordinate = 1e9f;

glm::vec3 vectorOption(const std::vector<float>& values, const char* name) {
  if (values.size() != 3 || !std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); })) {
    throw Error(std::string(name) + " takes three finite numbers X,Y,Z");
  }
  if (!std::all_of(values.begin(), values.end(), [](float v) { return std::fabs(v) <= kLargestCoordinate; })) {
    char given[96];
    std::snprintf(given, sizeof given, "%g,%g,%g", values[0], values[1], values[2]);
    throw Error(std::string(name) + " takes numbers within +-1e9, got " + given);
  }
  return {values[0], values[1], values[2]};
}

int frameDigits(int count) {
  int digits = 1;
  for (int n = count - 1; n >= 10; n /= 10) ++digits;
  return std::max(digits, 4);
}

// The full path of `program` on the PATH, or empty.
std::filesystem::path findOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    const std::filesystem::path candidate = std::filesystem::path(folder.empty() ? "." : folder) / program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

// The last non-empty line of a text file (what ffmpeg said last), or empty.
std::string lastLine(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

}  // namespace

void CameraOptions::addTo(CLI::App& command) {
  command.add_option("--look-from", lookFrom, "Camera position X,Y,Z, in place of the preset's")->delimiter(',');
  command.add_option("--look-at", lookAt, "Point the camera looks at, X,Y,Z, in place of the preset's")->delimiter(',');
  command.add_option("--up", up, "Camera up vector X,Y,Z, in place of the preset's")->delimiter(',');
  command.add_option("--fov", fov, "Vertical field of view in degrees, in (0, 180), in place of the preset's");
}

scene::Camera CameraOptions::applyTo(const scene::Camera& preset) const {
  scene::Camera camera = preset;
  if (!lookFrom.empty()) camera.position = vectorOption(lookFrom, "--look-from");
  if (!lookAt.empty()) camera.target = vectorOption(lookAt, "--look-at");
  if (!up.empty()) camera.up = vectorOption(up, "--up");
  if (fov) {
    if (!(*fov > 0.0f && *fov < 180.0f)) throw Error("--fov must be in (0, 180) degrees");
    camera.projection = scene::Camera::Projection::Perspective;
    camera.verticalFovDegrees = *fov;
  }
  const glm::vec3 view = camera.target - camera.position;
  if (!(glm::length(view) > 0.0f)) throw Error("the camera's position and look-at point are the same");
  if (!(glm::length(camera.up) > 0.0f)) throw Error("--up must not be zero");
  // Up along the view leaves the image's roll undefined (and the frame's basis NaN).
  const float sine = glm::length(glm::cross(glm::normalize(view), glm::normalize(camera.up)));
  if (!(sine > 1e-4f)) throw Error("the camera's up vector is along its view direction");
  return camera;
}

void OrbitOptions::addTo(CLI::App& command) {
  command.add_option("--orbit", frames,
                     "Write N numbered frames of a turntable about the camera's up vector through the look-at point "
                     "(--look-at) or the scene's centre");
  command.add_option("--orbit-degrees", degrees, "Angle the turntable turns over its N frames (default 360)");
}

void OrbitOptions::validate() const {
  if (frames && (*frames < 1 || *frames > 100000)) throw Error("--orbit must be in [1, 100000]");
  if (degrees && !frames) throw Error("--orbit-degrees needs --orbit N");
  if (degrees && !(std::abs(*degrees) <= 3600.0f)) throw Error("--orbit-degrees must be a number in [-3600, 3600]");
}

std::vector<scene::Camera> OrbitOptions::cameras(const scene::Camera& camera, glm::vec3 pivot) const {
  std::vector<scene::Camera> result;
  const int count = frames.value_or(1);
  const float step = glm::radians(degrees.value_or(360.0f)) / static_cast<float>(count);
  for (int k = 0; k < count; ++k) result.push_back(scene::turntableCamera(camera, pivot, step * static_cast<float>(k)));
  return result;
}

glm::vec3 orbitPivot(const scene::Scene& scene, const CameraOptions& camera) {
  if (!camera.lookAt.empty()) return vectorOption(camera.lookAt, "--look-at");
  return 0.5f * (scene.boundsMin() + scene.boundsMax());
}

std::vector<std::filesystem::path> OrbitOptions::framePaths(const std::filesystem::path& output,
                                                           const std::string& extension) const {
  if (!enabled()) return {output};
  std::vector<std::filesystem::path> paths;
  for (int f = 0; f < *frames; ++f) paths.push_back(sequenceFramePath(output, f, *frames, extension));
  return paths;
}

std::filesystem::path sequenceFramePath(const std::filesystem::path& output, int index, int count,
                                        const std::string& extension) {
  char number[16];
  std::snprintf(number, sizeof number, "-%0*d", frameDigits(count), index);
  std::filesystem::path frame = output;
  frame.replace_filename(output.stem().string() + number + extension);
  return frame;
}

bool isVideoPath(const std::filesystem::path& output) { return lowercaseExtension(output) == ".mp4"; }

bool encodeVideo(const std::filesystem::path& video, int count) {
  const std::filesystem::path ffmpeg = findOnPath("ffmpeg");
  if (ffmpeg.empty()) {
    std::fprintf(stderr, "glint: ffmpeg was not found, so %s was not made: the frames are the output (apt-get install ffmpeg)\n",
                 video.string().c_str());
    return false;
  }
  // ffmpeg's numbered input: the frames' path with its own '%' doubled, the number as %0Nd.
  std::string pattern;
  for (char c : (video.parent_path() / video.stem()).string()) pattern += c == '%' ? std::string("%%") : std::string(1, c);
  pattern += "-%0" + std::to_string(frameDigits(count)) + "d.png";
  const std::string temporary = video.string() + ".tmp" + std::to_string(::getpid());
  const std::filesystem::path log = temporary + ".log";
  const std::vector<std::string> arguments = {ffmpeg.string(), "-nostdin", "-y", "-loglevel", "error", "-framerate", "24",
                                              "-i", pattern, "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                              // H.264 in 4:2:0 needs even sides.
                                              "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-f", "mp4", temporary};
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, ffmpeg.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  const bool ran = spawned == 0 && ::waitpid(pid, &status, 0) == pid;
  const std::string said = lastLine(log);
  std::error_code ignored;
  std::filesystem::remove(log, ignored);
  if (!ran || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::filesystem::remove(temporary, ignored);
    throw Error(video.string() + ": ffmpeg could not make the video" + (said.empty() ? "" : " (" + said + ")"));
  }
  std::error_code renamed;
  std::filesystem::rename(temporary, video, renamed);
  if (renamed) {
    std::filesystem::remove(temporary, ignored);
    throw Error(video.string() + ": cannot write (" + renamed.message() + ")");
  }
  return true;
}

}  // namespace glint::app
