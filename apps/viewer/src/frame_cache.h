// The last picture of the scene, kept as a texture and drawn again while nothing the renderer
// reads has changed. On software GL a frame of 300K triangles with MSAA takes 80-120 ms; most
// frames of an interactive session only move the pointer or change a panel, and then cost a
// textured quad. Needs a current OpenGL 3.3 core context.
#pragma once

#include <cstdint>

#include "lapis/geometry/camera.h"
#include "lapis/viewer/scene.h"

namespace lapis::viewer {

class FrameCache {
 public:
  FrameCache();
  ~FrameCache();
  FrameCache(const FrameCache&) = delete;
  FrameCache& operator=(const FrameCache&) = delete;

  // Draws the stored picture into the current framebuffer when it was stored with `signature`
  // at this size; returns false (drawing nothing) otherwise.
  bool draw(std::uint64_t signature, int width, int height);
  // Stores the current framebuffer's colour (resolving MSAA) as the picture of `signature`.
  void store(std::uint64_t signature, int width, int height);

 private:
  unsigned texture_ = 0, framebuffer_ = 0, program_ = 0, vao_ = 0;
  int width_ = 0, height_ = 0;
  std::uint64_t signature_ = 0;
  bool valid_ = false;
};

}  // namespace lapis::viewer
