// What the hair app draws: the head (scalp tinted on request, the selected detail's region), the strands with
// root-to-tip colour, the style curves, the stroke preview, the selected curve's supporting surface and field glyphs on
// a slice.
#include <chrono>
#include <cstdint>

#include "hair_sketch_app.h"
#include "lapis/hair_sketch/sketch.h"
#include "lapis/hair_sketch/style_field.h"
#include "lapis/hair_sketch/symmetry.h"
#include "primitive_geometry.h"
#include "strand_display.h"

namespace lapis::hair_app {
namespace {

// Per-strand variation of colour, the same at every regrowth and budget: brightness in
// 0.8..1.15 and a slight shift between warmer and cooler (real hair varies in melanin mix).
Eigen::Vector3f strand_color_variation(int strand) {
  const auto hash = static_cast<std::uint32_t>(strand) * 2654435761u;
  const float k = 0.8f + 0.35f * static_cast<float>(hash >> 8) / static_cast<float>(1u << 24);
  const float warm = static_cast<float>((hash * 2246822519u) >> 8) / static_cast<float>(1u << 24) - 0.5f;
  return k * Eigen::Vector3f(1.0f + 0.10f * warm, 1.0f, 1.0f - 0.12f * warm);
}

Eigen::Vector3f curve_color(const StylePrimitive& p, bool selected) {
  if (selected) return {1.0f, 0.85f, 0.2f};
  if (std::holds_alternative<StreamCurve>(p.shape)) return {0.25f, 0.65f, 1.0f};
  if (std::holds_alternative<DividingCurve>(p.shape)) return {0.3f, 0.95f, 0.5f};
  return {0.95f, 0.4f, 0.85f};
}

}  // namespace

void HairSketchApp::update_head_item(viewer::Viewer& v) {
  auto& item = v.scene().meshes["head"];
  item.mesh = head_.mesh;
  item.base_color = {0.86f, 0.70f, 0.60f};  // skin
  item.colors.resize(0, 3);
  if (show_strands_ && !show_scalp_) {
    // Under the hair the scalp takes the roots' colour, as hair renderers do: a few thousand
    // strands cover far less of the scalp than a real head's hundred thousand, and bare skin
    // between them reads as a bald patch. The share of scalp faces around a vertex softens
    // the hairline.
    Eigen::VectorXf scalp = Eigen::VectorXf::Zero(head_.mesh.V.rows()), faces = scalp;
    for (Eigen::Index f = 0; f < head_.mesh.F.rows(); ++f)
      for (int k = 0; k < 3; ++k) {
        faces[head_.mesh.F(f, k)] += 1;
        if (head_.scalp_face[static_cast<size_t>(f)]) scalp[head_.mesh.F(f, k)] += 1;
      }
    item.colors.resize(head_.mesh.V.rows(), 3);
    for (Eigen::Index i = 0; i < head_.mesh.V.rows(); ++i) {
      const float w = 0.85f * (faces[i] > 0 ? scalp[i] / faces[i] : 0.0f);
      item.colors.row(i) = ((1 - w) * item.base_color + w * root_color_).transpose();
    }
  }
  if (show_scalp_) {
    item.colors = item.base_color.transpose().replicate(head_.mesh.V.rows(), 1);
    for (Eigen::Index f = 0; f < head_.mesh.F.rows(); ++f)
      if (head_.scalp_face[static_cast<size_t>(f)])
        for (int k = 0; k < 3; ++k) item.colors.row(head_.mesh.F(f, k)) << 0.55f, 0.62f, 0.85f;
  }
  // The selected detail's region, and what the brush paints into it.
  const auto& details = document_.style().details;
  const bool has_detail = selected_detail_ >= 0 && selected_detail_ < static_cast<int>(details.size());
  if (has_detail && (!details[selected_detail_].region.empty() || !painted_.empty())) {
    if (item.colors.rows() == 0) item.colors = item.base_color.transpose().replicate(head_.mesh.V.rows(), 1);
    for (const int i : details[selected_detail_].region) item.colors.row(i) << 0.95f, 0.55f, 0.2f;
    for (const int i : painted_) item.colors.row(i) << 1.0f, 0.75f, 0.3f;
  }
  ++item.version;
  head_dirty_ = false;
}

void HairSketchApp::update_strand_item(viewer::Viewer& v, const Strands& strands, int subset_stride) {
  auto& item = v.scene().lines["strands"];
  std::vector<int> source;
  StrandDisplayOptions options{.max_segments = static_cast<int>(strand_budget_.value()),
                               .current_stride = shown_stride_};
  if (subset_stride > 0) options.stride = 1;  // the subset is what is shown
  shown_stride_ = subset_stride > 0 ? subset_stride : display_stride(strands, options);
  const Strands shown = display_strands(strands, options, &source);
  if (subset_stride > 0)
    for (int& s : source) s *= subset_stride;  // the strand's index in the whole set, for its colour
  shown_strands_ = shown.count();
  const int n = static_cast<int>(shown.points.size());
  item.points.resize(n, 3);
  item.colors.resize(n, 3);
  item.strip_offsets = shown.offsets;
  for (int s = 0; s < shown.count(); ++s) {
    const int a = shown.offsets[static_cast<size_t>(s)], b = shown.offsets[static_cast<size_t>(s) + 1];
    const Eigen::Vector3f variation = strand_color_variation(source[static_cast<size_t>(s)]);
    for (int i = a; i < b; ++i) {
      item.points.row(i) = shown.points[static_cast<size_t>(i)].transpose();
      const float t = b - a > 1 ? static_cast<float>(i - a) / static_cast<float>(b - a - 1) : 0.0f;
      item.colors.row(i) = ((1 - t) * root_color_ + t * tip_color_).cwiseProduct(variation).cwiseMin(1.0f).transpose();
    }
  }
  const bool ribbons = strand_look_ == StrandLook::Ribbons;
  item.light.clear();
  if (ribbons && self_shadowing_) {
    // From the strands shown, not all of them: the occlusion is relative to the hair's mean
    // density (strand_occlusion.h), so a subset lights the same, and costs a fraction.
    const auto start = std::chrono::steady_clock::now();
    item.light = StrandOcclusion(shown).transmittance(shown);
    occlusion_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  item.shading = ribbons ? viewer::LineShading::HairRibbons : viewer::LineShading::KajiyaKay;
  item.width = strand_width_;
  item.tip_width = 0.35f;
  item.alpha = ribbons ? 1.0f : 0.9f;
  item.visible = show_strands_;
  ++item.version;
}

// A finished picture shows the hair on the head: every strand, no curves, previews or markers.
void HairSketchApp::prepare_picture(viewer::Viewer& v) {
  auto& scene = v.scene();
  for (auto& [name, item] : scene.lines) item.visible = name == "strands" && show_strands_;
  for (auto& [name, item] : scene.points) item.visible = false;
  scene.meshes.erase("support");
  strand_budget_.pin(0);
  if (last_) update_strand_item(v, last_->update.strands);
}

void HairSketchApp::update_curve_items(viewer::Viewer& v) {
  auto& curves = v.scene().lines["curves"];
  curves.clear();
  const auto& prims = document_.style().primitives;
  for (size_t i = 0; i < prims.size(); ++i) {
    if (hidden_.count(static_cast<int>(i))) continue;
    const Eigen::Vector3f color = curve_color(prims[i], static_cast<int>(i) == selected_);
    for (const auto& line : primitive_polylines(prims[i])) curves.add_strip(line, color);
    if (prims[i].mirrored)  // the twin, dimmer: it follows the primitive
      for (const auto& line : primitive_polylines(mirror_image(prims[i], head_.center.x())))
        curves.add_strip(line, 0.6f * color);
  }
  curves.width = 3.0f;
  curves.visible = show_curves_;
  ++curves.version;

  // The selected curve's supporting surface, translucent, while editing with hint strokes.
  auto& meshes = v.scene().meshes;
  meshes.erase("support");
  if (tool_ == Tool::Hint && selected_ >= 0 && selected_ < static_cast<int>(prims.size())) {
    try {
      const StylePrimitive& p = prims[static_cast<size_t>(selected_)];
      const SupportingSurface surf = make_supporting_surface(*editable_curve(p), p.viewpoint, p.support,
                                                             sketch_options(grid_, document_.style().settings));
      auto& m = meshes["support"];
      const int n = static_cast<int>(surf.points.size());
      m.mesh.V.resize(2 * n, 3);
      for (int i = 0; i < n; ++i) {
        m.mesh.V.row(2 * i) = (surf.points[i] - surf.half_width * surf.rulings[i]).transpose();
        m.mesh.V.row(2 * i + 1) = (surf.points[i] + surf.half_width * surf.rulings[i]).transpose();
      }
      m.mesh.F.resize(2 * (n - 1), 3);
      for (int i = 0; i + 1 < n; ++i) {
        m.mesh.F.row(2 * i) << 2 * i, 2 * i + 1, 2 * i + 2;
        m.mesh.F.row(2 * i + 1) << 2 * i + 1, 2 * i + 3, 2 * i + 2;
      }
      m.base_color = {0.4f, 0.7f, 1.0f};
      m.alpha = 0.3f;
      ++m.version;
    } catch (const Error&) {
      meshes.erase("support");  // degenerate seen from its viewpoint: nothing to show
    }
  }
  curves_dirty_ = false;
}

void HairSketchApp::update_preview_item(viewer::Viewer& v) {
  auto& item = v.scene().lines["preview"];
  item.clear();
  item.on_top = true;
  item.width = 2.5f;
  const auto cam = v.camera_matrices();
  // Raw strokes sit just behind the near plane, where they cover what is under the mouse.
  auto screen_line = [&](const Stroke& s) {
    std::vector<Eigen::Vector3d> pts;
    for (const auto& p : s) pts.push_back(geometry::unproject(cam, p.x(), p.y(), 0.05));
    return pts;
  };
  for (const auto& s : ponytail_strokes_) item.add_strip(screen_line(s), {0.95f, 0.4f, 0.85f});
  if (drawing_) {
    if (preview_.size() >= 2)
      item.add_strip(preview_, {1.0f, 0.95f, 0.4f});
    else if (stroke_.size() >= 2)
      item.add_strip(screen_line(stroke_), {1.0f, 1.0f, 1.0f});
  }
  ++item.version;
}

void HairSketchApp::update_glyph_item(viewer::Viewer& v) {
  auto& item = v.scene().lines["glyphs"];
  item.clear();
  item.visible = show_glyphs_;
  if (!show_glyphs_ || !last_ || !last_->field) return;
  const Grid& g = last_->grid;
  const Field& f = *last_->field;
  const int k = g.dims[2] / 2;  // the slice through the head's middle (constant z)
  for (int j = 0; j < g.dims[1]; ++j)
    for (int i = 0; i < g.dims[0]; ++i) {
      const int node = g.index(i, j, k);
      const Eigen::Vector3d t = f.row(node).transpose();
      if (t.norm() < 1e-3) continue;
      const Eigen::Vector3d p = g.position(node);
      const float m = static_cast<float>(std::min(1.0, t.norm()));
      item.add_strip(std::vector<Eigen::Vector3d>{p, p + 0.8 * g.spacing * t.normalized()},
                     {0.3f + 0.7f * m, 0.9f - 0.5f * m, 0.3f});
    }
  item.width = 1.5f;
  ++item.version;
}

}  // namespace lapis::hair_app
