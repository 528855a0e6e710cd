// PNG files for screenshots: write (atomically) and read back (tests compare pixels).
#pragma once

#include <cstdint>
#include <filesystem>

#include <vector>
#include "lapis/core/error.h"

namespace lapis::viewer {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // row-major, top row first
};

void write_png(const std::filesystem::path& path, const Image& image);
Image read_png(const std::filesystem::path& path);

}  // namespace lapis::viewer
