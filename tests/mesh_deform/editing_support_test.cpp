// What interactive editing needs from the module: selection files shared with the CLI, painted
// labels, per-vertex distortion for colour maps, the method list, the implicit preview.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/live_deformer.h"
#include "lapis/mesh_deform/methods.h"
#include "lapis/mesh_deform/selection_io.h"
#include "lapis/mesh_deform/vertex_distortion.h"
#include "lapis/mesh_deform/vertex_labels.h"
#include "test_meshes.h"

using namespace lapis::mesh_deform;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("lapis_mesh_deform_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// The box bar with its bottom tenth fixed (outside the ROI) and its top tenth the handle.
Selection bar_selection(const TriMesh& m) {
  Selection s;
  const double zmax = m.V.col(2).maxCoeff();
  std::vector<int> top;
  for (int v = 0; v < m.num_vertices(); ++v) {
    if (m.V(v, 2) > 0.1 * zmax) s.roi.push_back(v);
    if (m.V(v, 2) > 0.9 * zmax) top.push_back(v);
  }
  s.region_handles = {top};
  return s;
}

Eigen::Matrix4d turn(double radians, double shift) {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(radians, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T(1, 3) = shift;
  return T;
}

}  // namespace

TEST_CASE("mesh_deform: selection files round-trip every bit of a drag and read the CLI's formats") {
  const fs::path d = scratch();
  Selection s;
  s.region_handles = {{3, 4, 5}, {9}};
  s.point_handles = {7};
  std::vector<HandleTransforms> frames(2);
  frames[0].regions = {turn(0.1, 1.0 / 3), Eigen::Matrix4d::Identity()};
  frames[0].points = {Eigen::Vector3d(0.1, 0.2, 1e-17)};
  frames[1].regions = {turn(M_PI / 7, -2.0 / 7), turn(1e-3, 0)};
  frames[1].points = {Eigen::Vector3d(-0.3, 0.7, 5)};
  write_handles(d / "h.json", s, frames);
  const Drag back = read_handles(d / "h.json");
  CHECK(back.selection.region_handles == s.region_handles);
  CHECK(back.selection.point_handles == s.point_handles);
  REQUIRE(back.frames.size() == 2);
  for (size_t k = 0; k < 2; ++k) {
    for (size_t h = 0; h < 2; ++h) CHECK(back.frames[k].regions[h] == frames[k].regions[h]);  // exactly
    CHECK(back.frames[k].points[0] == frames[k].points[0]);
  }
  const std::vector<int> roi{0, 1, 2, 3, 4, 5, 7, 9, 100, 17};
  write_roi(d / "roi.txt", roi);
  CHECK(read_roi(d / "roi.txt") == roi);
  std::ofstream(d / "roi.json") << "[4, 2, 8]";
  CHECK(read_roi(d / "roi.json") == std::vector<int>{4, 2, 8});
  // A held handle (one transform) beside a dragged one: held for every frame.
  std::ofstream(d / "held.json")
      << R"({"regions": [{"vertices": [1], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]},
                                                    {"vertices": [2], "transforms": [[[1,0,0,1],[0,1,0,0],[0,0,1,0],[0,0,0,1]],
                                                                                     [[1,0,0,2],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]}]})";
  const Drag held = read_handles(d / "held.json");
  REQUIRE(held.frames.size() == 2);
  CHECK(held.frames[1].regions[0] == Eigen::Matrix4d::Identity());
  CHECK(held.frames[1].regions[1](0, 3) == 2);
}

TEST_CASE("mesh_deform: malformed selection files are IoErrors naming the file") {
  const fs::path d = scratch();
  std::ofstream(d / "bad_roi.txt") << "1 2 x 4";
  CHECK_THROWS_WITH_AS(read_roi(d / "bad_roi.txt"),
                       doctest::Contains("bad_roi.txt: ROI entry 2: expected an integer in [0, 2147483647], found 'x'"),
                       lapis::IoError);
  CHECK_THROWS_WITH_AS(read_roi(d / "missing.txt"), doctest::Contains("cannot open ROI file"), lapis::IoError);
  std::ofstream(d / "bad_m.json")
      << R"({"regions": [{"vertices": [1], "transforms": [[[1,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]}]})";
  CHECK_THROWS_WITH_AS(read_handles(d / "bad_m.json"),
                       doctest::Contains("region handle 0: expected 4 rows of 4 numbers"), lapis::IoError);
  std::ofstream(d / "counts.json") << R"({"regions": [{"vertices": [1], "transforms": [
      [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]], [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]},
      {"vertices": [2], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]], [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]],
      [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]}]})";
  CHECK_THROWS_WITH_AS(read_handles(d / "counts.json"), doctest::Contains("different frame counts"), lapis::IoError);
  Selection s;
  s.region_handles = {{1}};
  CHECK_THROWS_AS(write_handles(d / "x.json", s, {HandleTransforms{}}), lapis::InvalidArgument);
}

TEST_CASE("mesh_deform: painted labels give an ROI with its handles inside, or everything not fixed") {
  VertexLabels labels(10);
  labels.paint({0, 1}, VertexLabels::kFixed);
  labels.paint({8, 9}, 1);  // handle label 1; label 0 unused
  LabelledSelection s = to_selection(labels);
  CHECK(s.selection.roi == std::vector<int>{2, 3, 4, 5, 6, 7, 8, 9});  // no ROI painted: all but fixed
  REQUIRE(s.selection.region_handles.size() == 1);
  CHECK(s.selection.region_handles[0] == std::vector<int>{8, 9});
  CHECK(s.handle_label == std::vector<int>{1});
  labels.paint({4, 5}, VertexLabels::kRoi);
  s = to_selection(labels);
  CHECK(s.selection.roi == std::vector<int>{4, 5, 8, 9});  // painted ROI plus the handle
  labels.paint({8, 9}, VertexLabels::kNone);
  CHECK_THROWS_WITH_AS(to_selection(labels), "mesh_deform::to_selection(): no handle painted", lapis::InvalidArgument);
  CHECK_THROWS_AS(labels.paint({10}, 0), lapis::InvalidArgument);
  // From files: point handles become one-vertex region handles after the regions.
  Selection f;
  f.roi = {1, 2, 3};
  f.region_handles = {{3}};
  f.point_handles = {6};
  const VertexLabels l = from_selection(f, 8);
  CHECK(l.with(VertexLabels::kRoi) == std::vector<int>{1, 2});
  CHECK(l.with(0) == std::vector<int>{3});
  CHECK(l.with(1) == std::vector<int>{6});
  CHECK(l.handle_count() == 2);
}

TEST_CASE("mesh_deform: per-vertex distortion is zero under rigid motion and shows where a stretch happened") {
  const TriMesh m = test::box_bar(3, 1.0, 2.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vertices X = (m.V * R.transpose()).rowwise() + Eigen::RowVector3d(1, 2, 3);
  for (DistortionField f : {DistortionField::EdgeLength, DistortionField::Angle, DistortionField::LaplacianLength}) {
    CAPTURE(to_string(f));
    CHECK(vertex_distortion(m, X, f).cwiseAbs().maxCoeff() < 1e-9);
  }
  // Stretch the top half along z: edges there change, the bottom's do not.
  Vertices S = m.V;
  for (int v = 0; v < S.rows(); ++v)
    if (S(v, 2) > 1) S(v, 2) = 1 + 2 * (S(v, 2) - 1);
  const Eigen::VectorXd e = vertex_distortion(m, S, DistortionField::EdgeLength);
  const Eigen::VectorXd a = vertex_distortion(m, S, DistortionField::Angle);
  for (int v = 0; v < S.rows(); ++v) {
    if (m.V(v, 2) < 0.9) CHECK(std::max(e(v), a(v)) < 1e-12);
    const bool side = m.V(v, 2) > 1.1 && m.V(v, 2) < 1.9;  // on the stretched side walls (the top cap only moves)
    if (side) CHECK(e(v) > 0.1);
    if (side) CHECK(a(v) > 0.05);
  }
  CHECK_THROWS_AS(vertex_distortion(m, S.topRows(2), DistortionField::Angle), lapis::InvalidArgument);
}

TEST_CASE("mesh_deform: the method list makes every method and the preview equals the first system alone") {
  CHECK(methods().size() == 6);
  CHECK(method_from_name("edge") == Method::Edge);
  CHECK(method_from_name("salient") == Method::Salient);
  CHECK(method_from_name("isolines") == Method::Isolines);
  CHECK(method_from_name("arap") == Method::Arap);
  CHECK_THROWS_WITH_AS(method_from_name("magic"),
                       doctest::Contains("expected one of naive, implicit, arap, edge, salient, isolines"),
                       lapis::InvalidArgument);
  const TriMesh m = test::box_bar(3, 1.0, 4.0);
  const Selection sel = bar_selection(m);
  for (const MethodInfo& info : methods()) {
    MethodSettings s;
    s.method = info.method;
    s.arap_iterations = 2;
    auto d = make_deformer(m, s);
    CHECK(d->name() == info.name);
    d->set_selection(sel);
    const Vertices X = d->deform({{turn(0.3, 0.5)}, {}});
    const double off = (X.row(sel.region_handles[0][0]).transpose() -
                        apply(turn(0.3, 0.5), m.V.row(sel.region_handles[0][0]).transpose()))
                           .norm();
    CHECK(off < (info.method == Method::Salient ? 0.1 : 1e-9));  // Zhao et al.'s handles are soft (Eq. 4)
  }
  // Preview on a full-pipeline deformer = a first-system-only deformer, frame for frame; off
  // again = the full pipeline, without a new setup.
  ImplicitLaplacianDeformer full(m), first(m, ImplicitOptions{.shearing = ShearingRemoval::None});
  ImplicitLaplacianDeformer reference(m);
  for (auto* d : {&full, &first, &reference}) d->set_selection(sel), d->precompute();
  full.set_preview(true);
  const Vertices a = full.deform({{turn(0.4, 0.2)}, {}}), b = first.deform({{turn(0.4, 0.2)}, {}});
  CHECK((a - b).cwiseAbs().maxCoeff() < 1e-12);
  full.set_preview(false);
  (void)reference.deform({{turn(0.4, 0.2)}, {}});
  const Vertices c = full.deform({{turn(0.5, 0.2)}, {}}), r = reference.deform({{turn(0.5, 0.2)}, {}});
  CHECK(!full.dirty());
  CHECK((c - r).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((c - b).cwiseAbs().maxCoeff() > 1e-6);
}

TEST_CASE("mesh_deform: a live deformer sets up once per selection and its history replays to the same result") {
  const TriMesh m = test::box_bar(3, 1.0, 4.0);
  LiveDeformer live(m);
  LiveRequest r;
  r.settings.method = Method::Implicit;
  r.selection = bar_selection(m);
  r.selection_revision = 1;
  r.field = DistortionField::EdgeLength;
  std::vector<Eigen::Matrix4d> drag;
  LiveFrame f;
  for (int k = 1; k <= 4; ++k) {
    r.transforms = {{turn(0.5 * k, 0.1 * k)}, {}};  // past 90°: the implicit method's guide system
    r.preview = k < 4;                              // preview while dragging, full on release
    f = live.update(r);
    CHECK(f.did_setup == (k == 1));
    CHECK(f.preview == (k < 4));
    CHECK(f.distortion.size() == m.num_vertices());
  }
  REQUIRE(f.history.size() == 4);
  // A fresh deformer fed the recorded frames (what `lapis deform` does with the handles file).
  auto d = make_deformer(m, r.settings);
  d->set_selection(r.selection);
  Vertices X;
  for (const auto& t : f.history) X = d->deform(t);
  CHECK((X - f.positions).cwiseAbs().maxCoeff() < 1e-9);
  // A new selection revision sets up again and restarts the history.
  r.selection_revision = 2;
  f = live.update(r);
  CHECK(f.did_setup);
  CHECK(f.history.size() == 1);
  // A bad selection throws; the live deformer recovers with a good one.
  r.selection.region_handles = {{0}};  // vertex 0 is fixed (outside the ROI)
  r.selection_revision = 3;
  CHECK_THROWS_WITH_AS(live.update(r), doctest::Contains("is outside the ROI"), lapis::InvalidArgument);
  r.selection = bar_selection(m);
  r.selection_revision = 4;
  CHECK(live.update(r).did_setup);
}

TEST_CASE("mesh_deform: live ARAP frames of one pose lower the energy they report to convergence, and replay") {
  const TriMesh m = test::box_bar(3, 1.0, 4.0);
  LiveDeformer live(m);
  LiveRequest r;
  r.settings.method = Method::Arap;
  r.settings.arap_iterations = 2;
  r.selection = bar_selection(m);
  r.selection_revision = 1;
  r.transforms = {{turn(1.0, 0.2)}, {}};
  std::vector<double> energy;
  LiveFrame f;
  for (int k = 0; k < 30; ++k) energy.push_back((f = live.update(r)).energy);
  CHECK(energy.front() > 0);
  // Local-global steps never raise the energy; warm-started frames go on where the last stopped.
  for (size_t k = 1; k < energy.size(); ++k) CHECK(energy[k] <= energy[k - 1] * (1 + 1e-12));
  const double first = (energy[0] - energy[1]) / energy[0], last = (energy[28] - energy[29]) / energy[28];
  CHECK(last < 0.1 * first);
  // The frames are the history: a fresh deformer fed them lands on the same shape.
  auto d = make_deformer(m, r.settings);
  d->set_selection(r.selection);
  Vertices X;
  for (const auto& t : f.history) X = d->deform(t);
  CHECK((X - f.positions).cwiseAbs().maxCoeff() < 1e-12);
  r.settings.method = Method::Implicit;
  CHECK(live.update(r).energy == -1);
}

TEST_CASE("mesh_deform: growing and shrinking labels by rings works on what acts as ROI, fixed or handle") {
  const TriMesh grid = test::planar_grid(10, 10, 0.0);  // vertex j * 10 + i
  const lapis::geometry::Connectivity conn(grid);
  auto column = [](int i) {
    std::vector<int> c;
    for (int j = 0; j < 10; ++j) c.push_back(j * 10 + i);
    return c;
  };
  VertexLabels labels(100);
  labels.paint(column(0), VertexLabels::kFixed);
  labels.paint(column(9), 0);
  // No ROI painted: the ROI is columns 1-8; growing the fixed region takes column 1.
  grow_labels(labels, conn, VertexLabels::kFixed, 1);
  CHECK(labels.acting_as(VertexLabels::kFixed).size() == 20);
  CHECK(labels.acting_as(VertexLabels::kRoi).size() == 70);
  // Growing the ROI takes the fixed columns back but never the handle.
  grow_labels(labels, conn, VertexLabels::kRoi, 5);
  CHECK(labels.acting_as(VertexLabels::kFixed).empty());
  CHECK(labels.acting_as(0) == column(9));
  // Shrinking the handle by a ring gives its border to the ROI: column 9 has no interior, so
  // it all goes, but grown first by two it keeps one column.
  grow_labels(labels, conn, 0, 2);
  CHECK(labels.acting_as(0).size() == 30);
  grow_labels(labels, conn, 0, -1);
  CHECK(labels.acting_as(0).size() == 20);
  // With an ROI painted, unpainted vertices are fixed; shrinking the ROI makes its border fixed.
  VertexLabels painted(100);
  std::vector<int> middle;
  for (int i = 3; i <= 6; ++i)
    for (int v : column(i)) middle.push_back(v);
  painted.paint(middle, VertexLabels::kRoi);
  grow_labels(painted, conn, VertexLabels::kRoi, -1);
  CHECK(painted.acting_as(VertexLabels::kRoi).size() == 20);  // columns 4 and 5
  CHECK(painted.acting_as(VertexLabels::kFixed).size() == 80);
  CHECK_THROWS_AS(grow_labels(painted, lapis::geometry::Connectivity(test::planar_grid(3, 3, 0.0)), 0, 1),
                  lapis::InvalidArgument);
}

TEST_CASE("mesh_deform: selection files refuse indices that would wrap or truncate and numbers that are not finite") {
  const fs::path d = scratch();
  const auto refuses = [&](const std::string& name, const std::string& text, const std::string& message, auto read) {
    CAPTURE(name);
    std::ofstream(d / name) << text;
    CHECK_THROWS_WITH_AS(read(d / name), doctest::Contains(message.c_str()), lapis::IoError);
  };
  const auto roi = [](const fs::path& p) { return read_roi(p); };
  const auto handles = [](const fs::path& p) { return read_handles(p); };
  refuses("wrap.txt", "1 4294967296 3", "ROI entry 1: expected an integer in [0, 2147483647], found 4294967296", roi);
  refuses("negative.txt", "-1", "ROI entry 0: expected an integer in [0, 2147483647], found -1", roi);
  refuses("fraction.txt", "2 1.5", "ROI entry 1: expected an integer in [0, 2147483647], found '1.5'", roi);
  refuses("fraction.json", "[1, 5.7]", "ROI[1]: expected an integer in [0, 2147483647], found '5.7'", roi);
  refuses("huge.json", "[1e20]", "ROI[0]: expected an integer in [0, 2147483647], found '1e+20'", roi);
  refuses("wrap.json", "[4294967296]", "ROI[0]: expected an integer in [0, 2147483647], found 4294967296", roi);
  const std::string identity = "[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]";
  refuses("point.json", R"({"points": [{"vertex": 4294967301, "translations": [[0, 0, 1]]}]})",
          "point handle 0: vertex: expected an integer in [0, 2147483647], found 4294967301", handles);
  refuses("point_frac.json", R"({"points": [{"vertex": 1.5, "translations": [[0, 0, 1]]}]})",
          "point handle 0: vertex: expected an integer in [0, 2147483647], found '1.5'", handles);
  refuses("region.json", R"({"regions": [{"vertices": [1, 4294967301], "transforms": [)" + identity + "]}]}",
          "region handle 0: vertices[1]: expected an integer in [0, 2147483647], found 4294967301", handles);
  refuses("translation.json", R"({"points": [{"vertex": 1, "translations": [[0, "a", 1]]}]})",
          "point handle 0: translation 0 y: expected a finite number, found", handles);
  refuses("short.json", R"({"points": [{"vertex": 1, "translations": [[0, 1]]}]})",
          "point handle 0: translation 0: expected 3 numbers", handles);
}
