// lapis.hair_sketch in Python: a hairstyle session (settings, head, style primitives) loaded
// from or saved to its JSON file, primitives added from 3D points, the field solved and the
// strands grown in one build() (thesis ch. 4), strands as a flat (n, 3) float32 points array
// plus per-strand offsets (the layout of .hair files), and the .hair / OBJ exports. The per-edit
// loop, lapis.LiveHairstyle, is in hair_live.cpp.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <optional>
#include <string>

#include "bindings.h"
#include "hair_session.h"
#include "lapis/geometry/camera.h"
#include "lapis/hair_sketch/export.h"
#include "lapis/hair_sketch/hair_file.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/stroke_commands.h"
#include "lapis/hair_sketch/style_field.h"
#include "strands.h"

namespace lapis::python {
namespace {

using namespace lapis::hair_sketch;
using namespace pybind11::literals;

std::vector<Eigen::Vector3d> to_points(const py::handle& obj, const char* name) {
  const geometry::Vertices P = to_vertices(obj, name);
  std::vector<Eigen::Vector3d> out(static_cast<size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) out[static_cast<size_t>(i)] = P.row(i).transpose();
  return out;
}

Eigen::Vector3d to_point(const py::handle& obj, const char* name) {
  const Eigen::VectorXd p = to_vector(obj, name);
  if (p.size() != 3) throw py::value_error(std::string(name) + " must have shape (3,)");
  return p;
}

void add(Session& s, StylePrimitive p, const py::object& viewpoint) {
  p.viewpoint = viewpoint.is_none() ? geometry::eye_position(s.style.camera) : to_point(viewpoint, "viewpoint");
  p.support = s.style.settings.support;
  s.style.primitives.push_back(std::move(p));
}

py::dict build(const Session& s) {
  HairstyleResult r;
  {
    py::gil_scoped_release release;
    r = build_hairstyle(s.style, s.head);
  }
  py::tuple strands = strands_to_numpy(std::move(r.strands));
  const std::array<int, 3> d = r.grid.dims;
  py::array field =
      to_numpy(std::move(r.field)).reshape({py::ssize_t{d[2]}, py::ssize_t{d[1]}, py::ssize_t{d[0]}, py::ssize_t{3}});
  return py::dict("points"_a = strands[0], "offsets"_a = strands[1], "field"_a = field,
                  "grid"_a = py::dict("origin"_a = to_numpy(Eigen::VectorXd(r.grid.origin)),
                                      "spacing"_a = r.grid.spacing, "dims"_a = py::make_tuple(d[0], d[1], d[2])),
                  "constraints"_a = r.constraints, "penetrating_segments"_a = r.penetrating_segments,
                  "timings_ms"_a = py::dict("grid"_a = r.grid_ms, "solve"_a = r.solve_ms, "growth"_a = r.growth_ms,
                                            "detail"_a = r.detail_ms, "penetration"_a = r.penetration_ms));
}

void bind_session(py::module_& m) {
  // Named as in session files.
  py::enum_<hair_field::FieldMethod>(m, "FieldMethod", "How the style field is solved per edit (thesis §4.4.2).")
      .value("auto", hair_field::FieldMethod::Auto, "thesis while its factor fits, else multigrid")
      .value("thesis", hair_field::FieldMethod::Thesis, "Cholesky update/downdate of the changed constraints")
      .value("refactorize", hair_field::FieldMethod::Refactorize, "a numeric refactorization per edit")
      .value("multigrid", hair_field::FieldMethod::Multigrid, "warm-started PCG with a multigrid V-cycle");
  py::class_<Session>(m, "HairSession", R"(A hairstyle session (thesis ch. 4): settings, the head, style primitives.

    s = lapis.HairSession.load("assets/sessions/parting.json")   # replays its strokes
    s.add_stream_curve([[0, 1.0, 0.2], [0, 1.1, -0.4], [0, 0.6, -0.9]])
    r = s.build()             # the field solved, the strands grown (GIL released)
    lapis.write_hair("out.hair", r["points"], r["offsets"])

build() returns a dict: points (n, 3) float32 and offsets (strands + 1,) int32 (strand i is
points[offsets[i]:offsets[i + 1]]), the field (dims z, y, x, 3) with its grid, counts, timings.)")
      .def_static(
          "load",
          [](const std::filesystem::path& path, const py::object& head_mesh, bool replay) {
            // None, not an empty path: an empty default would reach C++ as "." (pathlib's spelling).
            const std::filesystem::path head =
                head_mesh.is_none() ? std::filesystem::path() : head_mesh.cast<std::filesystem::path>();
            py::gil_scoped_release release;
            Hairstyle style = load_session(path);
            Head h = load_session_head(style, path, head);
            if (replay && !style.strokes.empty()) style = replay_strokes(style, h);
            return Session{std::move(style), std::move(h)};
          },
          "path"_a, "head"_a = py::none(), "replay"_a = true,
          "Loads a session file and its head (or `head`, a mesh path); replay: rebuild the primitives from the "
          "recorded strokes, as `lapis hair` does.")
      .def(
          "replay",
          [](Session& s) {
            py::gil_scoped_release release;
            s.style = replay_strokes(s.style, s.head);
          },
          "Rebuilds the primitives from the recorded strokes with the current settings (the sketch spacing is "
          "the grid's, so set grid_unknowns first, as `lapis hair --grid-unknowns` does).")
      .def(
          "save",
          [](const Session& s, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            save_session(path, s.style);
          },
          "path"_a, "Saves the session (atomic, numbers round-trip exactly).")
      .def_property_readonly(
          "primitives",
          [](const Session& s) {
            py::list out;
            for (const StylePrimitive& p : s.style.primitives) out.append(primitive_type(p));
            return out;
          },
          "The primitives' types in order: 'stream_curve', 'dividing_curve', 'ponytail'.")
      .def_property_readonly(
          "details",
          [](const Session& s) {
            py::list out;
            for (const StrandDetail& d : s.style.details) out.append(detail_type(d));
            return out;
          },
          "The strand details applied after growth, in order (thesis §4.7): 'curl', 'wave', 'clump', 'frizz', "
          "'length', 'cut'. They come from the session file; build() and LiveHairstyle apply them.")
      .def(
          "remove_primitive",
          [](Session& s, int i) {
            if (i < 0 || i >= static_cast<int>(s.style.primitives.size()))
              throw InvalidArgument("lapis.HairSession.remove_primitive(): index " + std::to_string(i) +
                                    " is out of range");
            s.style.primitives.erase(s.style.primitives.begin() + i);
          },
          "index"_a, "Removes primitive `index` (an index into .primitives).")
      .def(
          "add_stream_curve",
          [](Session& s, const py::handle& points, int tail_segments, const py::object& viewpoint) {
            add(s, {StreamCurve{to_points(points, "points"), tail_segments}}, viewpoint);
          },
          "points"_a, "tail_segments"_a = 0, "viewpoint"_a = py::none(),
          "A stream curve (§4.5) from (n, 3) points, scalp outward; viewpoint: of its supporting surface "
          "(default: the session camera's eye, as when it is sketched).")
      .def(
          "add_dividing_curve",
          [](Session& s, const py::handle& points, double alpha0, double alpha1, const py::object& viewpoint) {
            DividingCurve c;
            c.points = to_points(points, "points");
            c.alpha0 = alpha0, c.alpha1 = alpha1;
            add(s, {c}, viewpoint);
          },
          "points"_a, "alpha0"_a = 0.0, "alpha1"_a = 0.0, "viewpoint"_a = py::none(),
          "A dividing curve (§4.5, Fig. 4.4) on the scalp from (n, 3) points, tilted by alpha0 / alpha1 radians.")
      .def(
          "add_ponytail",
          [](Session& s, const py::handle& spine, const py::handle& section, const py::handle& a, const py::handle& b,
             const py::object& viewpoint) {
            Ponytail p;
            p.spine = to_points(spine, "spine");
            p.cross_section = to_points(section, "cross_section");
            p.profile_a = to_points(a, "profile_a");
            p.profile_b = to_points(b, "profile_b");
            add(s, {p}, viewpoint);
          },
          "spine"_a, "cross_section"_a, "profile_a"_a, "profile_b"_a, "viewpoint"_a = py::none(),
          "A ponytail (§4.5) from its four curves, each (n, 3).")
      .def_property(
          "grid_unknowns", [](const Session& s) { return s.style.settings.grid.target_unknowns; },
          [](Session& s, double n) { s.style.settings.grid.target_unknowns = n; }, "Grid unknowns (thesis §4.6).")
      .def_property(
          "roots", [](const Session& s) { return s.style.settings.roots.count; },
          [](Session& s, int n) { s.style.settings.roots.count = n; }, "Strands to grow.")
      .def_property(
          "field_method", [](const Session& s) { return s.style.settings.field_method; },
          [](Session& s, hair_field::FieldMethod f) { s.style.settings.field_method = f; },
          "lapis.FieldMethod of the field solves.")
      .def("build", &build, "Solves the field and grows the strands from scratch; see the class docstring.");
}

// A number (the file's default) or one value per point of a .hair attribute with
// `components` floats per point.
void set_attribute(const py::object& value, const char* name, size_t points, int components, std::vector<float>& array,
                   float* defaults) {
  if (value.is_none()) return;
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a) throw py::type_error(std::string(name) + " must be a number or an array of numbers");
  const bool one = components == 1 ? a.ndim() == 0 : a.ndim() == 1 && a.shape(0) == components;
  if (one) {
    std::copy(a.data(), a.data() + components, defaults);
    return;
  }
  const bool per_point = components == 1
                             ? a.ndim() == 1 && static_cast<size_t>(a.shape(0)) == points
                             : a.ndim() == 2 && static_cast<size_t>(a.shape(0)) == points && a.shape(1) == components;
  if (!per_point)
    throw py::value_error(std::string(name) + " must be " + (components == 1 ? "a number" : "an RGB triple") +
                          " or have shape (" + std::to_string(points) + (components == 1 ? ",)" : ", 3)") + ", not " +
                          shape_text(a));
  array.assign(a.data(), a.data() + a.size());
}

void write_hair(const std::filesystem::path& path, const py::handle& points, const py::handle& offsets,
                const py::object& thickness, const py::object& transparency, const py::object& colors,
                const py::object& info) {
  HairFile f = to_hair_file(strands_from_numpy(points, offsets));
  set_attribute(thickness, "thickness", f.point_count, 1, f.thickness, &f.default_thickness);
  set_attribute(transparency, "transparency", f.point_count, 1, f.transparency, &f.default_transparency);
  set_attribute(colors, "colors", f.point_count, 3, f.colors, f.default_color.data());
  if (!info.is_none()) f.info = info.cast<std::string>();
  py::gil_scoped_release release;
  write_hair_file(path, f);
}

// One attribute per point: the file's array, or its default repeated.
py::array attribute(std::vector<float>&& array, const float* defaults, size_t points, int components) {
  if (array.empty())
    for (size_t i = 0; i < points; ++i) array.insert(array.end(), defaults, defaults + components);
  py::array a = to_numpy(std::move(array));
  return components == 1 ? a : a.reshape({static_cast<py::ssize_t>(points), py::ssize_t{components}});
}

py::dict read_hair_attributes(const std::filesystem::path& path) {
  HairFile f;
  {
    py::gil_scoped_release release;
    f = read_hair_file(path);
  }
  const size_t n = f.point_count;
  return py::dict("thickness"_a = attribute(std::move(f.thickness), &f.default_thickness, n, 1),
                  "transparency"_a = attribute(std::move(f.transparency), &f.default_transparency, n, 1),
                  "colors"_a = attribute(std::move(f.colors), f.default_color.data(), n, 3), "info"_a = f.info);
}

}  // namespace

void bind_hair(py::module_& m) {
  bind_session(m);
  m.def("write_hair", &write_hair, "path"_a, "points"_a, "offsets"_a, "thickness"_a = py::none(),
        "transparency"_a = py::none(), "colors"_a = py::none(), "info"_a = py::none(),
        R"(Writes strands (points (n, 3) float32, offsets) as a .hair file (Cem Yuksel's format).

thickness, transparency: a number (the file's default for every point) or one value per point
(n,); colors: an RGB triple (the default) or (n, 3); info: up to 87 characters of text.)");
  m.def(
      "read_hair",
      [](const std::filesystem::path& path) {
        Strands s;
        {
          py::gil_scoped_release release;
          s = strands_from_hair_file(read_hair_file(path));
        }
        return strands_to_numpy(std::move(s));
      },
      "path"_a, "A .hair file's strands as (points (n, 3) float32, offsets (strands + 1,) int32).");
  m.def("read_hair_attributes", &read_hair_attributes, "path"_a,
        R"(A .hair file's per-point attributes: {'thickness': (n,), 'transparency': (n,),
'colors': (n, 3)} float32, the file's defaults where it stores no array, and its 'info' text.)");
  m.def(
      "write_strands_obj",
      [](const std::filesystem::path& path, const py::handle& points, const py::handle& offsets) {
        const Strands s = strands_from_numpy(points, offsets);
        py::gil_scoped_release release;
        write_strands_obj(path, s);
      },
      "path"_a, "points"_a, "offsets"_a, "Writes strands as OBJ polylines (strands of one point are skipped).");
}

}  // namespace lapis::python
