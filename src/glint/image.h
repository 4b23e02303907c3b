// 8-bit RGB images and PNG output (stb_image_write), written all-or-nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace glint {

struct Rgb8 {
  std::uint8_t r, g, b;
};

class ImageRgb8 {
 public:
  ImageRgb8(int width, int height, Rgb8 fill);
  int width() const { return width_; }
  int height() const { return height_; }
  Rgb8& at(int x, int y) { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  const Rgb8& at(int x, int y) const { return pixels_[static_cast<std::size_t>(y) * width_ + x]; }
  // Drawing, clipped to the image.
  void fillRect(int x0, int y0, int x1, int y1, Rgb8 colour);
  void drawLine(float x0, float y0, float x1, float y1, Rgb8 colour, float width = 1.5f);
  // Text in stb_easy_font's bitmap font, `scale` pixels per font unit; returns the text's width.
  int drawText(int x, int y, const char* text, Rgb8 colour, int scale = 2);
  static int textWidth(const char* text, int scale = 2);

  const std::uint8_t* data() const { return &pixels_.front().r; }

 private:
  int width_;
  int height_;
  std::vector<Rgb8> pixels_;
};

// 8-bit pixels (`channels` 1 to 4 per pixel, rows from the top, tightly packed) as PNG bytes
// (stb_image_write); throws Error when encoding fails. The one PNG encoder: writePng and the glTF
// writer's embedded textures use it.
std::vector<std::byte> encodePng(int width, int height, int channels, const std::uint8_t* pixels);
// An 8-bit RGB image's PNG bytes.
std::vector<std::byte> encodePng(const ImageRgb8& image);

// Throws Error naming the file when it cannot be written; leaves no partial file.
void writePng(const std::filesystem::path& path, const ImageRgb8& image);

}  // namespace glint
