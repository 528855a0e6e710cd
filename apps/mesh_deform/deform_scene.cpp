// What the deform app draws: the surface coloured by selection (ROI, fixed, handles), by a
// distortion measure or by saliency, the salient features over it, the gizmo on the active handle, the degenerate
// vertices the implicit method found, the lasso being drawn, the painted vertices through the
// surface in x-ray, and the handle vertices the ROI's border comes close to.
#include "deform_app.h"
#include "lapis/viewer/colormap.h"

namespace lapis::deform_app {
namespace {

const Eigen::Vector3f kRoiColor{0.82f, 0.77f, 0.70f};    // the part that deforms: warm clay
const Eigen::Vector3f kFixedColor{0.42f, 0.46f, 0.55f};  // outside the ROI: slate
const Eigen::Vector3f kHandleColors[] = {{1.0f, 0.55f, 0.12f}, {0.85f, 0.25f, 0.75f}, {0.25f, 0.75f, 0.35f},
                                         {0.2f, 0.7f, 0.95f},  {0.95f, 0.85f, 0.2f},  {0.6f, 0.4f, 0.95f}};

// Salient features: cool tones, apart from the handles' warm ones.
const Eigen::Vector3f kFeatureColors[] = {{0.2f, 0.45f, 0.95f}, {0.1f, 0.7f, 0.6f},  {0.55f, 0.3f, 0.9f},
                                          {0.3f, 0.8f, 0.95f},  {0.2f, 0.55f, 0.3f}, {0.7f, 0.55f, 0.95f}};

}  // namespace

Eigen::Vector3f handle_color(int label) { return kHandleColors[label % 6]; }
Eigen::Vector3f fixed_color() { return kFixedColor; }
Eigen::Vector3f feature_color(int index) { return kFeatureColors[index % 6]; }

void DeformApp::update_surface(viewer::Viewer& v) {
  auto& item = v.scene().meshes["surface"];
  item.mesh = shown_;
  const int n = rest_.num_vertices();
  item.colors.resize(n, 3);
  const bool distortion =
      color_mode_ == ColorMode::Distortion && last_ && last_->frame.distortion.size() == n && !stroke_;
  const bool saliency = color_mode_ == ColorMode::Saliency && last_ && last_->frame.saliency.size() == n;
  const bool field = color_mode_ == ColorMode::IsolineField && isoline_field_.size() == n && !stroke_;
  const bool rigidity = color_mode_ == ColorMode::Rigidity && rigidity_.size() == n && !stroke_;
  if (distortion) {
    item.colors = viewer::colorize(last_->frame.distortion, 0.0, legend_hi_);
  } else if (saliency) {
    const Eigen::VectorXd& s = last_->frame.saliency;
    item.colors = viewer::colorize(s, viewer::percentile(s, 0.02), viewer::percentile(s, 0.98));
  } else if (field) {
    item.colors = viewer::colorize(isoline_field_, 0.0, 1.0);
  } else if (rigidity) {
    item.colors = viewer::colorize(rigidity_, 0.0, std::max(1e-12, viewer::percentile(rigidity_, 0.95)));
  } else {
    const VertexLabels& labels = stroke_ ? *stroke_ : *state_.labels;
    const bool roi_painted = labels.any(VertexLabels::kRoi);
    for (int i = 0; i < n; ++i) {
      const int l = labels.label[static_cast<size_t>(i)];
      // Shown as what the vertex is for the deformer: unpainted vertices are ROI unless an
      // ROI was painted (then they are fixed).
      const bool fixed = l == VertexLabels::kFixed || (l == VertexLabels::kNone && roi_painted);
      item.colors.row(i) = (l >= 0 ? handle_color(l) : fixed ? kFixedColor : kRoiColor).transpose();
    }
  }
  // The salient method's features over any colouring, half blended, so they show where they are.
  const std::vector<int>& painted = feature_stroke_ ? *feature_stroke_ : features_.feature_of;
  if (settings_.method == Method::Salient && static_cast<int>(painted.size()) == n)
    for (int i = 0; i < n; ++i)
      if (const int f = painted[static_cast<size_t>(i)]; f >= 0)
        item.colors.row(i) = 0.5f * (item.colors.row(i) + feature_color(f).transpose());
  // X-ray: the surface translucent and the painted vertices drawn over it, hidden ones too.
  item.alpha = xray_ ? 0.45f : 1.0f;
  auto& painted_points = v.scene().points["x-ray painted"];
  painted_points.visible = xray_;
  if (xray_) {
    const VertexLabels& labels = stroke_ ? *stroke_ : *state_.labels;
    std::vector<int> shown;
    for (int i = 0; i < n; ++i)
      if (labels.label[static_cast<size_t>(i)] != VertexLabels::kNone) shown.push_back(i);
    painted_points.points.resize(static_cast<Eigen::Index>(shown.size()), 3);
    painted_points.colors.resize(static_cast<Eigen::Index>(shown.size()), 3);
    for (size_t k = 0; k < shown.size(); ++k) {
      const int i = shown[k], l = labels.label[static_cast<size_t>(i)];
      painted_points.points.row(static_cast<Eigen::Index>(k)) = shown_.V.row(i).cast<float>();
      painted_points.colors.row(static_cast<Eigen::Index>(k)) = (l >= 0                      ? handle_color(l)
                                                                 : l == VertexLabels::kFixed ? kFixedColor
                                                                                             : kRoiColor)
                                                                    .transpose();
    }
    painted_points.size = 3.0f;
  }
  ++painted_points.version;
  ++item.version;
  surface_dirty_ = false;
}

bool DeformApp::gizmo_shown() const { return selection_ && state_.labels->any(state_.active_handle); }

void DeformApp::update_gizmo(viewer::Viewer& v) {
  auto& item = v.scene().lines["gizmo"];
  item.visible = gizmo_shown();
  if (!item.visible) return;
  // The gizmo sits on the active handle where its transform puts it.
  const Eigen::Vector3d c = handle_rest_centroid(state_.active_handle);
  const Eigen::Matrix4d& T = state_.transforms[static_cast<size_t>(state_.active_handle)];
  gizmo_.set_center(T.topLeftCorner<3, 3>() * c + T.topRightCorner<3, 1>());
  gizmo_.draw(v.camera_matrices(), item);
}

void DeformApp::update_markers(viewer::Viewer& v) {
  auto& points = v.scene().points["degenerate"];
  points.points.resize(0, 3);
  if (show_degenerate_ && last_) {
    const auto& d = last_->frame.degenerate_vertices;
    points.points.resize(static_cast<Eigen::Index>(d.size()), 3);
    for (size_t k = 0; k < d.size(); ++k)
      points.points.row(static_cast<Eigen::Index>(k)) = shown_.V.row(d[k]).cast<float>();
  }
  points.base_color = {1.0f, 0.2f, 0.2f};
  points.size = 6.0f;
  points.on_top = false;
  ++points.version;

  // The handle vertices the ROI's border passes close to (update_roi_warning).
  auto& warned = v.scene().points["roi warning"];
  warned.points.resize(static_cast<Eigen::Index>(warned_vertices_.size()), 3);
  for (size_t k = 0; k < warned_vertices_.size(); ++k)
    warned.points.row(static_cast<Eigen::Index>(k)) = shown_.V.row(warned_vertices_[k]).cast<float>();
  warned.base_color = {1.0f, 0.15f, 0.1f};
  warned.size = 7.0f;
  ++warned.version;

  // The isolines of the method's first set, where the deformed surface carries them.
  auto& iso = v.scene().lines["isolines"];
  iso.clear();
  if ((color_mode_ == ColorMode::IsolineField || color_mode_ == ColorMode::Rigidity) &&
      isoline_field_.size() == rest_.num_vertices())
    for (const auto& seg : isolines_)
      iso.add_strip({mesh_deform::isoline_point(shown_.V, shown_.F, seg.face, seg.p),
                     mesh_deform::isoline_point(shown_.V, shown_.F, seg.face, seg.q)},
                    {0.1f, 0.1f, 0.1f});
  iso.width = 1.5f;
  ++iso.version;

  // The lasso, just behind the near plane so it covers what it encloses.
  auto& lasso = v.scene().lines["lasso"];
  lasso.clear();
  if (lasso_.size() >= 2) {
    const auto cam = v.camera_matrices();
    std::vector<Eigen::Vector3d> pts;
    for (const auto& p : lasso_) pts.push_back(geometry::unproject(cam, p.x(), p.y(), 0.05));
    pts.push_back(pts.front());
    lasso.add_strip(pts, {1.0f, 1.0f, 1.0f});
  }
  lasso.on_top = true;
  lasso.width = 2.0f;
  markers_dirty_ = false;
}

void DeformApp::update_target_surface(viewer::Viewer& v) {
  auto& item = v.scene().meshes["transfer target"];
  item.mesh = geometry::TriMesh{target_shown_, pairing_->target().F};
  item.visible = show_target_;
  // Coloured like the source: each paired region in its handle's colour, the rest as ROI.
  item.colors = kRoiColor.transpose().replicate(pairing_->target().num_vertices(), 1);
  auto& seeds = v.scene().points["transfer seeds"];
  seeds.points.resize(0, 3);
  seeds.colors.resize(0, 3);
  for (const PairSlot& s : pairing_->slots()) {
    const Eigen::Vector3f c = s.label < 0 ? kFixedColor : handle_color(s.label);
    for (int i : s.region) item.colors.row(i) = c.transpose();
    for (int seed : s.seeds) {  // the clicks, lighter than their regions
      seeds.points.conservativeResize(seeds.points.rows() + 1, 3);
      seeds.colors.conservativeResize(seeds.colors.rows() + 1, 3);
      seeds.points.row(seeds.points.rows() - 1) = target_shown_.row(seed).cast<float>();
      seeds.colors.row(seeds.colors.rows() - 1) = (0.6f * c + Eigen::Vector3f::Constant(0.4f)).transpose();
    }
  }
  seeds.size = 9.0f;
  seeds.visible = show_target_;
  ++item.version;
  ++seeds.version;
  target_dirty_ = false;
}

}  // namespace lapis::deform_app
