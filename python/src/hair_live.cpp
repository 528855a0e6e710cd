// lapis.LiveHairstyle: the interactive loop of thesis ch. 4 from Python. Set up once for a
// session's head and settings, then each update() brings the field and the strands up to date
// with the session's current primitives: only the constraint diff reaches the solver (§4.4.2)
// and the strands regrow into the storage of strands Python has dropped (StrandPool), as the
// sketching app regrows them.
#include <pybind11/stl.h>

#include <memory>
#include <utility>
#include <vector>

#include "bindings.h"
#include "hair_session.h"
#include "lapis/hair_sketch/live_hairstyle.h"
#include "strands.h"

namespace lapis::python {
namespace {

using namespace lapis::hair_sketch;
using namespace pybind11::literals;

struct Live {
  py::object session;  // the lapis.HairSession followed, kept alive: the C++ object reads its head
  std::unique_ptr<LiveHairstyle> live;
  std::shared_ptr<StrandPool> pool = std::make_shared<StrandPool>();
};

Live make_live(const py::object& session) {
  const Session& s = session.cast<const Session&>();
  Live l{session, nullptr};
  py::gil_scoped_release release;
  l.live = std::make_unique<LiveHairstyle>(s.head, s.style.settings);
  return l;
}

py::dict solve_dict(const hair_field::FieldSolveReport& r) {
  return py::dict("method"_a = hair_field::to_string(r.method), "added"_a = r.added, "removed"_a = r.removed,
                  "changed"_a = r.changed, "iterations"_a = r.iterations, "error_estimate"_a = r.error_estimate,
                  "detail"_a = r.detail, "update_ms"_a = r.update_ms, "solve_ms"_a = r.solve_ms,
                  "total_ms"_a = r.total_ms);
}

py::dict update_dict(Live& l, LiveUpdate u) {
  py::tuple strands = strands_to_numpy(std::move(u.strands), l.pool);
  py::list solves;
  for (const hair_field::FieldSolveReport& r : u.solves) solves.append(solve_dict(r));
  return py::dict("points"_a = strands[0], "offsets"_a = strands[1], "constraints"_a = u.constraints,
                  "solves"_a = solves, "regrown"_a = u.regrown,
                  "timings_ms"_a = py::dict("solve"_a = u.solve_ms, "growth"_a = u.growth_ms, "detail"_a = u.detail_ms,
                                            "total"_a = u.total_ms));
}

py::dict update(Live& l) {
  // Copied with the GIL held: another thread may edit the session while the field solves.
  const Hairstyle& style = l.session.cast<const Session&>().style;
  const std::vector<StylePrimitive> primitives = style.primitives;
  const std::vector<StrandDetail> details = style.details;
  Strands reuse = l.pool->take();
  LiveUpdate u;
  {
    py::gil_scoped_release release;
    u = l.live->update(primitives, details, std::move(reuse));
  }
  return update_dict(l, std::move(u));
}

py::dict preview(Live& l, int stride) {
  const Hairstyle& style = l.session.cast<const Session&>().style;
  const std::vector<StylePrimitive> primitives = style.primitives;
  const std::vector<StrandDetail> details = style.details;
  LiveUpdate u;
  {
    py::gil_scoped_release release;
    u = l.live->preview(primitives, details, stride);
  }
  return update_dict(l, std::move(u));
}

}  // namespace

void bind_hair_live(py::module_& m) {
  py::class_<Live>(m, "LiveHairstyle",
                   R"(The per-edit loop of hair sketching (thesis ch. 4), as the sketching app runs it.

    s = lapis.HairSession.load("assets/sessions/parting.json")
    live = lapis.LiveHairstyle(s)     # grid, field solver and roots for s's head and settings (GIL released)
    r = live.update()                 # the field and the strands for s's primitives
    s.add_stream_curve(points)
    r = live.update()                 # only the new curve's constraints reach the solver (§4.4.2)

update() returns a dict: points (n, 3) float32 and offsets (strands + 1,) int32 as
HairSession.build() returns them, the constraint count, the solves (the style field's, then
the scalp avoidance's: method, diff sizes, iterations, error estimate, timings), regrown
(False when the primitives were unchanged and only the session's strand details were applied
again) and timings_ms (solve, growth, detail, total). The strands regrow into the storage of an earlier result
whose arrays are gone, so drop old results to keep an edit loop fast. The settings (grid,
roots, field method) are the session's when the LiveHairstyle is made; make a new one after
changing them. Multigrid solves are iterative: after edits the field matches a from-scratch
build() to the solver's tolerance, not bit for bit.)")
      .def(py::init(&make_live), "session"_a)
      .def("update", &update, "Brings the field and the strands up to date with the session's primitives.")
      .def("preview", &preview, "stride"_a,
           "The strands of every stride-th root only (0, stride, 2·stride, ...), details applied, as update() "
           "grows them, point for point: what a view drawing that subset shows. Solves as update() does; the "
           "next update() then only grows the rest. Same dict as update().")
      .def_property_readonly(
          "roots",
          [](const Live& l) {
            geometry::Vertices R(static_cast<Eigen::Index>(l.live->roots().size()), 3);
            for (size_t i = 0; i < l.live->roots().size(); ++i)
              R.row(static_cast<Eigen::Index>(i)) = l.live->roots()[i].transpose();
            return to_numpy(std::move(R));
          },
          "The strands' roots on the scalp, (strands, 3) float64 (fixed for the object's life).")
      .def_property_readonly(
          "field",
          [](const Live& l) {
            const hair_field::Grid& g = l.live->grid();
            hair_field::Field f = l.live->field();
            return to_numpy(std::move(f))
                .reshape({py::ssize_t{g.dims[2]}, py::ssize_t{g.dims[1]}, py::ssize_t{g.dims[0]}, py::ssize_t{3}});
          },
          "A copy of the current field, (dims z, y, x, 3) float64, on the grid of HairSession.build().");
}

}  // namespace lapis::python
