// What the apps draw, as plain data: triangle meshes with per-vertex colours, thousands of
// line strips (strands, curves) and point sets. No GL here: app logic fills a Scene and
// tests inspect it without a display; a Renderer turns it into pixels. Each item carries a
// version that its owner bumps when the data changes, so renderers re-upload only then.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/camera.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::viewer {

using Points3f = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct MeshItem {
  geometry::TriMesh mesh;
  Points3f colors;  // #V by 3 per-vertex colours, or empty for base_color
  Eigen::Vector3f base_color{0.78f, 0.74f, 0.70f};
  float alpha = 1.0f;  // < 1 draws translucent, after the opaque items
  bool visible = true;
  std::uint64_t version = 0;
};

enum class LineShading {
  Flat,       // constant colour: curves, markers
  KajiyaKay,  // hair fibres as lines: Kajiya–Kay diffuse + specular around the strand tangent
  // Hair fibres as camera-facing ribbons: `width` pixels wide at the root tapering to
  // `tip_width` · `width` at the tip, anti-aliased edges (coverage, resolved by MSAA's
  // alpha-to-coverage, so no sorting), Kajiya–Kay with two highlights shifted along the strand
  // (the cuticle's tilt: a white one toward the root, a tinted one toward the tip) and each
  // point lit by `light` (self-shadowing).
  HairRibbons,
};

struct LineItem {
  Points3f points;                    // all strips, concatenated
  std::vector<int> strip_offsets{0};  // strip i is points[offsets[i], offsets[i+1])
  Points3f colors;                    // per point, or empty for base_color
  Eigen::Vector3f base_color{0.2f, 0.6f, 1.0f};
  float width = 1.0f;        // pixels
  float tip_width = 0.35f;   // HairRibbons: the width at a strip's end, as a fraction of `width`
  std::vector<float> light;  // HairRibbons: per point, the light reaching it in [0, 1], or empty: 1
  float alpha = 1.0f;
  LineShading shading = LineShading::Flat;
  bool on_top = false;  // ignore depth (previews, selections)
  bool visible = true;
  std::uint64_t version = 0;

  int num_strips() const { return static_cast<int>(strip_offsets.size()) - 1; }
  // Appends one strip.
  void add_strip(const std::vector<Eigen::Vector3f>& strip);
  // Appends one strip of one colour (colours of earlier strips default to base_color).
  void add_strip(const std::vector<Eigen::Vector3d>& strip, const Eigen::Vector3f& color);
  void clear();
};

struct PointItem {
  Points3f points;
  Points3f colors;
  Eigen::Vector3f base_color{1.0f, 0.3f, 0.2f};
  float size = 8.0f;  // pixels
  bool on_top = true;
  bool visible = true;
  std::uint64_t version = 0;
};

// Items by name; names order drawing within a kind.
struct Scene {
  std::map<std::string, MeshItem> meshes;
  std::map<std::string, LineItem> lines;
  std::map<std::string, PointItem> points;
  Eigen::Vector3f background{0.16f, 0.17f, 0.19f};

  // Bounding box of the visible meshes (or of everything when there is no mesh).
  bool bounds(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const;
};

// A hash of everything a renderer draws from: the items' names, versions (bumped by their
// owners when the data changes), visibility and the per-frame uniforms (colour, alpha, width,
// size, shading, drawing on top), the background, the camera and the framebuffer's size. Equal
// signatures mean the same picture, so a renderer may reuse the last one (frame_cache.h).
std::uint64_t scene_signature(const Scene& scene, const geometry::CameraMatrices& camera, int width, int height);
// The part of it that is the view alone: the camera and the framebuffer's size.
std::uint64_t camera_signature(const geometry::CameraMatrices& camera, int width, int height);

}  // namespace lapis::viewer
