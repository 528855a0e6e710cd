// Turns a Scene into pixels. The interface keeps app logic testable without a display:
// the OpenGL 3.3 renderer draws for real; CountingRenderer only counts what it was given.
#pragma once

#include <memory>

#include "lapis/geometry/camera.h"
#include "lapis/viewer/scene.h"

namespace lapis::viewer {

// What the last render() cost: the picture of an unchanged scene is drawn again from a cache
// (reused), else `triangles` triangles, `strips` line strips and `points` points were drawn.
struct RenderStats {
  bool reused = false;
  long triangles = 0, strips = 0, points = 0;
};

class Renderer {
 public:
  virtual ~Renderer() = default;
  // Draws the scene into the current framebuffer of the given pixel size.
  virtual void render(const Scene& scene, const geometry::CameraMatrices& camera, int width, int height) = 0;
  virtual RenderStats stats() const { return {}; }
  // Draws the scene as render() does but never from a cache, with every width and size given
  // in pixels multiplied by `pixel_scale`: the same picture at a higher resolution
  // (supersampling), or a tile of it (the projection then covers the tile only).
  virtual void render_uncached(const Scene& scene, const geometry::CameraMatrices& camera, int width, int height,
                               float pixel_scale) {
    (void)pixel_scale;
    render(scene, camera, width, height);
  }
};

// Needs a current OpenGL 3.3 core context (the Viewer makes one). With `frame_cache`, the
// picture of an unchanged scene (scene_signature()) is copied, not drawn again.
std::unique_ptr<Renderer> make_gl_renderer(bool frame_cache = true);

// No GL: records how much of each kind it was asked to draw.
class CountingRenderer : public Renderer {
 public:
  void render(const Scene& scene, const geometry::CameraMatrices&, int, int) override {
    ++frames;
    triangles = strips = points = 0;
    for (const auto& [n, m] : scene.meshes)
      if (m.visible) triangles += m.mesh.F.rows();
    for (const auto& [n, l] : scene.lines)
      if (l.visible) strips += l.num_strips();
    for (const auto& [n, p] : scene.points)
      if (p.visible) points += p.points.rows();
  }
  long frames = 0, triangles = 0, strips = 0, points = 0;
};

}  // namespace lapis::viewer
