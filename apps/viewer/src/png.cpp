#include "lapis/viewer/png.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <string>

#include "lapis/core/atomic_file.h"
#include "lapis/core/error.h"

namespace lapis::viewer {
namespace {

void append(void* context, void* data, int size) {
  static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}

}  // namespace

void write_png(const std::filesystem::path& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4)
    throw InvalidArgument("viewer::write_png(): " + path.string() + ": image is " + std::to_string(image.width) + "x" +
                          std::to_string(image.height) + " with " + std::to_string(image.rgba.size()) +
                          " bytes, expected 4 per pixel");
  core::write_file_atomically(path, [&](std::ostream& out) {
    if (!stbi_write_png_to_func(append, &out, image.width, image.height, 4, image.rgba.data(), image.width * 4))
      throw IoError("viewer::write_png(): " + path.string() + ": PNG encoding failed");
  });
}

Image read_png(const std::filesystem::path& path) {
  Image image;
  int channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &image.width, &image.height, &channels, 4);
  if (!data)
    throw IoError("viewer::read_png(): " + path.string() + ": " +
                  (stbi_failure_reason() ? stbi_failure_reason() : "cannot read"));
  image.rgba.assign(data, data + static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4);
  stbi_image_free(data);
  return image;
}

}  // namespace lapis::viewer
