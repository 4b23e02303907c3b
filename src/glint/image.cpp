#include "glint/image.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <stb_easy_font.h>
#include <stb_image_write.h>

#include "glint/error.h"
#include "glint/file_io.h"

namespace glint {

static_assert(sizeof(Rgb8) == 3, "ImageRgb8 rows must be tightly packed for PNG encoding");

ImageRgb8::ImageRgb8(int width, int height, Rgb8 fill)
    : width_(width), height_(height), pixels_(static_cast<std::size_t>(width) * height, fill) {}

void ImageRgb8::fillRect(int x0, int y0, int x1, int y1, Rgb8 colour) {
  for (int y = std::max(0, y0); y < std::min(height_, y1); ++y) {
    for (int x = std::max(0, x0); x < std::min(width_, x1); ++x) at(x, y) = colour;
  }
}

void ImageRgb8::drawLine(float x0, float y0, float x1, float y1, Rgb8 colour, float width) {
  // Coverage by distance to the segment, for a smooth line without a rasteriser library.
  const int minX = static_cast<int>(std::floor(std::min(x0, x1) - width));
  const int maxX = static_cast<int>(std::ceil(std::max(x0, x1) + width));
  const int minY = static_cast<int>(std::floor(std::min(y0, y1) - width));
  const int maxY = static_cast<int>(std::ceil(std::max(y0, y1) + width));
  const float dx = x1 - x0;
  const float dy = y1 - y0;
  const float length2 = std::max(dx * dx + dy * dy, 1e-12f);
  for (int y = std::max(0, minY); y <= std::min(height_ - 1, maxY); ++y) {
    for (int x = std::max(0, minX); x <= std::min(width_ - 1, maxX); ++x) {
      const float px = static_cast<float>(x) + 0.5f - x0;
      const float py = static_cast<float>(y) + 0.5f - y0;
      const float t = std::clamp((px * dx + py * dy) / length2, 0.0f, 1.0f);
      const float distance = std::hypot(px - t * dx, py - t * dy);
      const float coverage = std::clamp(0.5f * width + 0.5f - distance, 0.0f, 1.0f);
      if (coverage > 0.0f) {
        Rgb8& p = at(x, y);
        auto mix = [coverage](std::uint8_t a, std::uint8_t b) {
          return static_cast<std::uint8_t>(std::lround(a + (b - a) * coverage));
        };
        p = {mix(p.r, colour.r), mix(p.g, colour.g), mix(p.b, colour.b)};
      }
    }
  }
}

int ImageRgb8::drawText(int x, int y, const char* text, Rgb8 colour, int scale) {
  struct Vertex {
    float x, y, z;
    unsigned char rgba[4];
  };
  static thread_local Vertex vertices[4 * 2000];
  std::string copy(text);
  const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, vertices, sizeof vertices);
  for (int q = 0; q < quads; ++q) {
    const Vertex& a = vertices[4 * q];
    const Vertex& c = vertices[4 * q + 2];
    fillRect(x + static_cast<int>(a.x * scale), y + static_cast<int>(a.y * scale), x + static_cast<int>(c.x * scale),
             y + static_cast<int>(c.y * scale), colour);
  }
  return textWidth(text, scale);
}

int ImageRgb8::textWidth(const char* text, int scale) {
  std::string copy(text);
  return stb_easy_font_width(copy.data()) * scale;
}

std::vector<std::byte> encodePng(int width, int height, int channels, const std::uint8_t* pixels) {
  std::vector<std::byte> encoded;
  auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::byte>*>(context);
    const auto* bytes = static_cast<const std::byte*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
      !stbi_write_png_to_func(append, &encoded, width, height, channels, pixels, width * channels)) {
    throw Error("PNG encoding failed");
  }
  return encoded;
}

std::vector<std::byte> encodePng(const ImageRgb8& image) {
  return encodePng(image.width(), image.height(), 3, image.data());
}

void writePng(const std::filesystem::path& path, const ImageRgb8& image) {
  std::vector<std::byte> encoded;
  try {
    encoded = encodePng(image);
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
  writeFileAtomically(path, encoded);
}

}  // namespace glint
