// Finished pictures (--render): the scene without panels, supersampled. A picture of
// 2000×1500 at 3× supersampling and 4× MSAA would need a 6000×4500 multisampled framebuffer
// (≈ 0.9 GB, more than software GL gives), so it is drawn in tiles: each tile's projection is
// the camera's restricted to the tile, every pixel width is scaled by the supersampling, and
// each tile is averaged down (in linear light) into the picture as it is read back.
#pragma once

#include "lapis/geometry/camera.h"
#include "lapis/viewer/png.h"
#include "lapis/viewer/renderer.h"
#include "lapis/viewer/scene.h"

namespace lapis::viewer {

struct PictureOptions {
  int width = 2000, height = 1500;
  int supersample = 3;  // samples per output pixel along each axis
  int msaa = 4;         // on top of supersampling (ribbons turn coverage into samples); 0: none
  int tile = 0;         // tile side in output pixels; 0: 2048 samples (or the GL's limit) over supersample
};

// Needs a current OpenGL 3.3 core context. `camera` is the camera of the whole picture (its
// projection for width / height). Throws lapis::Error when the framebuffer cannot be made.
Image render_picture(Renderer& renderer, const Scene& scene, const geometry::CameraMatrices& camera,
                     const PictureOptions& options);

}  // namespace lapis::viewer
