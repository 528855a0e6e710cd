// Tiled, supersampled offscreen rendering (picture.h).
#define GL_GLEXT_PROTOTYPES
#include "picture.h"

#include <GL/gl.h>
#include <GL/glext.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "lapis/core/error.h"

namespace lapis::viewer {
namespace {

// A framebuffer with colour and depth renderbuffers, multisampled when samples > 0.
struct Framebuffer {
  GLuint fbo = 0, color = 0, depth = 0;
  Framebuffer(int width, int height, int samples, bool with_depth) {
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glGenRenderbuffers(1, &color);
    glBindRenderbuffer(GL_RENDERBUFFER, color);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color);
    if (with_depth) {
      glGenRenderbuffers(1, &depth);
      glBindRenderbuffer(GL_RENDERBUFFER, depth);
      glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    }
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      release();
      throw Error("viewer::render_picture(): cannot make a " + std::to_string(width) + "x" + std::to_string(height) +
                  " framebuffer with " + std::to_string(samples) + " samples");
    }
  }
  ~Framebuffer() { release(); }
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;
  void release() {
    if (depth) glDeleteRenderbuffers(1, &depth);
    if (color) glDeleteRenderbuffers(1, &color);
    if (fbo) glDeleteFramebuffers(1, &fbo);
    fbo = color = depth = 0;
  }
};

// The projection restricted to output pixels [x0, x1) × [y0, y1) (y up, as GL counts).
Eigen::Matrix4d tile_projection(const Eigen::Matrix4d& projection, int width, int height, int x0, int x1, int y0,
                                int y1) {
  auto ndc = [](int p, int size) { return 2.0 * p / size - 1.0; };
  const double l = ndc(x0, width), r = ndc(x1, width), b = ndc(y0, height), t = ndc(y1, height);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m(0, 0) = 2 / (r - l), m(0, 3) = -(r + l) / (r - l);
  m(1, 1) = 2 / (t - b), m(1, 3) = -(t + b) / (t - b);
  return m * projection;
}

struct Linear {
  std::array<float, 256> from_byte{};
  Linear() {
    for (int i = 0; i < 256; ++i) from_byte[static_cast<size_t>(i)] = std::pow(static_cast<float>(i) / 255.0f, 2.2f);
  }
  static std::uint8_t to_byte(float v) {
    return static_cast<std::uint8_t>(std::lround(255.0f * std::pow(std::clamp(v, 0.0f, 1.0f), 1.0f / 2.2f)));
  }
};

}  // namespace

Image render_picture(Renderer& renderer, const Scene& scene, const geometry::CameraMatrices& camera,
                     const PictureOptions& o) {
  if (o.width < 1 || o.height < 1 || o.supersample < 1 || o.msaa < 0 || o.tile < 0)
    throw Error("viewer::render_picture(): a picture needs a positive size and supersampling");
  GLint max_size = 0, max_samples = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  const int ss = o.supersample, samples = std::min(o.msaa, static_cast<int>(max_samples));
  const int largest = std::max(1, std::min(2048, static_cast<int>(max_size)) / ss);
  const int tile = o.tile > 0 ? std::min(o.tile, largest) : largest;  // output pixels per tile side
  Framebuffer drawn(tile * ss, tile * ss, samples, true);
  Framebuffer resolved(tile * ss, tile * ss, 0, false);

  static const Linear linear;
  Image image;
  image.width = o.width, image.height = o.height;
  image.rgba.assign(static_cast<size_t>(o.width) * static_cast<size_t>(o.height) * 4, 255);
  std::vector<std::uint8_t> raw(static_cast<size_t>(tile * ss) * static_cast<size_t>(tile * ss) * 4);
  for (int y0 = 0; y0 < o.height; y0 += tile)
    for (int x0 = 0; x0 < o.width; x0 += tile) {
      const int x1 = std::min(o.width, x0 + tile), y1 = std::min(o.height, y0 + tile);
      const int w = (x1 - x0) * ss, h = (y1 - y0) * ss;
      geometry::CameraMatrices part = camera;
      part.projection = tile_projection(camera.projection, o.width, o.height, x0, x1, y0, y1);
      glBindFramebuffer(GL_FRAMEBUFFER, drawn.fbo);
      renderer.render_uncached(scene, part, w, h, static_cast<float>(ss));
      glBindFramebuffer(GL_READ_FRAMEBUFFER, drawn.fbo);
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolved.fbo);
      glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
      glBindFramebuffer(GL_READ_FRAMEBUFFER, resolved.fbo);
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
      // Average each ss × ss block into one output pixel (GL's rows go up, the image's down).
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          float sum[3] = {0, 0, 0};
          for (int sy = 0; sy < ss; ++sy)
            for (int sx = 0; sx < ss; ++sx) {
              const size_t k = (static_cast<size_t>((y - y0) * ss + sy) * static_cast<size_t>(w) +
                                static_cast<size_t>((x - x0) * ss + sx)) *
                               4;
              for (int c = 0; c < 3; ++c) sum[c] += linear.from_byte[raw[k + static_cast<size_t>(c)]];
            }
          const size_t out =
              (static_cast<size_t>(o.height - 1 - y) * static_cast<size_t>(o.width) + static_cast<size_t>(x)) * 4;
          for (int c = 0; c < 3; ++c)
            image.rgba[out + static_cast<size_t>(c)] = Linear::to_byte(sum[c] / static_cast<float>(ss * ss));
        }
    }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  return image;
}

}  // namespace lapis::viewer
