#include "lapis/hair_sketch/strand_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "lapis/core/error.h"
#include "strand_detail_ops.h"

namespace lapis::hair_sketch {
namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

void require(bool ok, const std::string& fn, const std::string& what) {
  if (!ok) throw InvalidArgument(fn + ": " + what);
}
bool finite_in(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }
constexpr double kHuge = 1e6;  // lengths and rates beyond this are not hair

void check_shape(const CurlDetail& d, const std::string& fn) {
  require(finite_in(d.frequency, 1e-9, kHuge), fn, "curl frequency must be in (0, 1e6] turns per unit length");
  require(finite_in(d.radius, 0, kHuge), fn, "curl radius must be in [0, 1e6]");
  require(finite_in(d.frequency_growth, -0.99, kHuge), fn, "curl frequency_growth must be in [-0.99, 1e6]");
  require(finite_in(d.radius_growth, -1, kHuge), fn, "curl radius_growth must be in [-1, 1e6]");
  require(finite_in(d.phase_jitter, 0, 1), fn, "curl phase_jitter must be in [0, 1]");
  require(finite_in(d.radius_jitter, 0, 1), fn, "curl radius_jitter must be in [0, 1]");
  require(finite_in(d.root_fade, 0, kHuge), fn, "curl root_fade must be in [0, 1e6]");
}
void check_shape(const ClumpDetail& d, const std::string& fn) {
  require(d.clumps >= 1, fn, "clump count must be at least 1");
  require(finite_in(d.strength, 0, 1), fn, "clump strength must be in [0, 1]");
  require(finite_in(d.profile, 1e-3, 1e3), fn, "clump profile must be in [0.001, 1000]");
}
void check_shape(const FrizzDetail& d, const std::string& fn) {
  require(finite_in(d.amplitude, 0, kHuge), fn, "frizz amplitude must be in [0, 1e6]");
  require(finite_in(d.wavelength, 1e-9, kHuge), fn, "frizz wavelength must be in (0, 1e6]");
  require(finite_in(d.root_fade, 0, kHuge), fn, "frizz root_fade must be in [0, 1e6]");
}
void check_shape(const LengthDetail& d, const std::string& fn) {
  require(finite_in(d.variation, 0, 1), fn, "length variation must be in [0, 1]");
}
void check_shape(const CutDetail& d, const std::string& fn) {
  require(d.line.size() >= 2, fn, "a cut line needs at least two points");
  for (const auto& q : d.line) require(q.allFinite(), fn, "cut line points must be finite");
  require(d.camera.view.allFinite() && d.camera.projection.allFinite() && d.camera.viewport.allFinite() &&
              d.camera.viewport[2] > 0 && d.camera.viewport[3] > 0,
          fn, "the cut line's camera must be finite with a non-empty viewport");
}

}  // namespace

const char* detail_type(const StrandDetail& d) {
  return std::visit(Overloaded{[](const CurlDetail& c) { return c.helical ? "curl" : "wave"; },
                               [](const ClumpDetail&) { return "clump"; }, [](const FrizzDetail&) { return "frizz"; },
                               [](const LengthDetail&) { return "length"; }, [](const CutDetail&) { return "cut"; }},
                    d.shape);
}

namespace {

bool same(const CurlDetail& a, const CurlDetail& b) {
  return a.helical == b.helical && a.frequency == b.frequency && a.radius == b.radius &&
         a.frequency_growth == b.frequency_growth && a.radius_growth == b.radius_growth &&
         a.phase_jitter == b.phase_jitter && a.radius_jitter == b.radius_jitter && a.root_fade == b.root_fade;
}
bool same(const ClumpDetail& a, const ClumpDetail& b) {
  return a.clumps == b.clumps && a.strength == b.strength && a.profile == b.profile;
}
bool same(const FrizzDetail& a, const FrizzDetail& b) {
  return a.amplitude == b.amplitude && a.wavelength == b.wavelength && a.root_fade == b.root_fade;
}
bool same(const LengthDetail& a, const LengthDetail& b) { return a.variation == b.variation; }
bool same(const CutDetail& a, const CutDetail& b) {
  return a.camera.view == b.camera.view && a.camera.projection == b.camera.projection &&
         a.camera.viewport == b.camera.viewport && a.line == b.line;
}

}  // namespace

bool same_detail(const StrandDetail& a, const StrandDetail& b) {
  if (a.shape.index() != b.shape.index() || a.seed != b.seed || a.region != b.region) return false;
  return std::visit([&](const auto& x) { return same(x, std::get<std::decay_t<decltype(x)>>(b.shape)); }, a.shape);
}

void check_detail(const StrandDetail& d, int head_vertices, const std::string& fn) {
  std::visit([&](const auto& shape) { check_shape(shape, fn); }, d.shape);
  for (const int v : d.region)
    require(v >= 0 && v < head_vertices, fn,
            "detail region vertex " + std::to_string(v) + " is outside the head's " + std::to_string(head_vertices) +
                " vertices");
}

std::vector<int> nearest_head_vertices(const Head& head, const std::vector<Eigen::Vector3d>& roots) {
  std::vector<int> out(roots.size());
  const auto n = static_cast<std::ptrdiff_t>(roots.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const geometry::ClosestPoint c = head.bvh->closest_point(roots[i]);
    int corner = 0;
    c.barycentric.maxCoeff(&corner);
    out[i] = head.mesh.F(c.face, corner);
  }
  return out;
}

DetailContext detail_context(const Head& head, const std::vector<Eigen::Vector3d>& roots,
                             const HeadClearance* clearance, double head_clearance) {
  DetailContext c;
  c.root_vertex = nearest_head_vertices(head, roots);
  c.center = head.center.cast<float>();
  c.clearance = clearance;
  // As far out as growth lifts the roots (RootOptions::lift), so a faded-in offset never
  // counts as sinking, and no closer than growth keeps the strands (GrowthOptions::head_clearance),
  // so that a segment between two offset points does not cut through a curve of the scalp.
  c.min_clearance = static_cast<float>(0.5e-3 * head.box.diagonal().norm());
  if (clearance)
    c.min_clearance = std::max(c.min_clearance, static_cast<float>(head_clearance * clearance->grid().spacing));
  return c;
}

namespace {

std::vector<detail::Polyline> unpack(const Strands& s) {
  std::vector<detail::Polyline> out(s.count());
  for (int i = 0; i < s.count(); ++i)
    out[i].assign(s.points.begin() + s.offsets[i], s.points.begin() + s.offsets[i + 1]);
  return out;
}

Strands pack(const std::vector<detail::Polyline>& polylines) {
  Strands s;
  std::size_t total = 0;
  for (const auto& p : polylines) total += p.size();
  s.points.reserve(total);
  s.offsets.reserve(polylines.size() + 1);
  for (const auto& p : polylines) {
    s.points.insert(s.points.end(), p.begin(), p.end());
    s.offsets.push_back(static_cast<int>(s.points.size()));
  }
  return s;
}

int whole_index(const DetailContext& context, int i) {
  return context.strand_index.empty() ? i : context.strand_index[static_cast<std::size_t>(i)];
}

// Whether strand i of the whole set is in the detail's region.
class RegionTest {
 public:
  RegionTest(const StrandDetail& d, const DetailContext& context) : context_(context), everywhere_(d.region.empty()) {
    if (everywhere_) return;
    int top = 0;
    for (const int v : context.root_vertex) top = std::max(top, v + 1);
    in_region_.assign(top, 0);
    for (const int v : d.region)
      if (v < top) in_region_[v] = 1;
  }
  bool operator()(int whole) const { return everywhere_ || in_region_[context_.root_vertex[whole]]; }

 private:
  const DetailContext& context_;
  bool everywhere_;
  std::vector<char> in_region_;
};

std::vector<int> affected_strands(const StrandDetail& d, const std::vector<detail::Polyline>& strands,
                                  const DetailContext& context) {
  const RegionTest in_region(d, context);
  std::vector<int> out;
  for (int i = 0; i < static_cast<int>(strands.size()); ++i)
    if (strands[i].size() >= 2 && in_region(whole_index(context, i))) out.push_back(i);
  return out;
}

// A clump's guides in the whole set, chosen by the seed among every root in its region, grown
// or not: a subset of the strands can then know them before the rest have grown.
std::vector<int> clump_guides(const StrandDetail& d, const DetailContext& context) {
  const RegionTest in_region(d, context);
  std::vector<int> candidates;
  for (int w = 0; w < static_cast<int>(context.root_vertex.size()); ++w)
    if (in_region(w)) candidates.push_back(w);
  return detail::choose_guides(candidates, std::get<ClumpDetail>(d.shape).clumps, d.seed);
}

void apply_one(const StrandDetail& d, std::vector<detail::Polyline>& strands, const DetailContext& context) {
  const std::vector<int> affected = affected_strands(d, strands, context);
  if (const auto* clump = std::get_if<ClumpDetail>(&d.shape)) {
    std::vector<int> guides = clump_guides(d, context);
    if (!context.strand_index.empty())
      for (int& g : guides) {  // to positions in the subset
        const auto at = std::lower_bound(context.strand_index.begin(), context.strand_index.end(), g);
        if (at == context.strand_index.end() || *at != g)
          throw InvalidArgument("hair_sketch::apply_strand_detail(): the strands lack clump guide " +
                                std::to_string(g) + " (detail_guides() lists what a subset needs)");
        g = static_cast<int>(at - context.strand_index.begin());
      }
    detail::clump_strands(*clump, affected, guides, strands, context);
    return;
  }
  const auto n = static_cast<std::ptrdiff_t>(affected.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const int i = affected[k];
    const int index = whole_index(context, i);  // the strand's random streams
    detail::Polyline& p = strands[i];
    std::visit(Overloaded{[&](const CurlDetail& c) { p = detail::curl_strand(c, d.seed, index, p, context); },
                          [&](const FrizzDetail& f) { p = detail::frizz_strand(f, d.seed, index, p, context); },
                          [&](const LengthDetail& l) { p = detail::vary_length(l, d.seed, index, p); },
                          [&](const CutDetail& c) { p = detail::cut_strand(c, p); }, [](const ClumpDetail&) {}},
               d.shape);
  }
}

// Offsets keep every point clear of the head (keep_clear), but a curl wound close to the scalp
// can still cut through it between two clear points, where the scalp curves tighter than the
// curl's step. The last pass pushes out the middle of each segment whose middle is inside the
// head, as a new point. Strands that are clear (as grown ones are) stay as they are.
void keep_segments_outside(detail::Polyline& p, const DetailContext& context) {
  const HeadClearance& head = *context.clearance;
  const float floor = 0.5f * context.min_clearance;  // below what growth and offsets leave
  for (std::size_t i = 1; i < p.size(); ++i)
    if (head(p[i]) < floor) p[i] = head.push_out(p[i], context.min_clearance);
  for (std::size_t i = 1; i < p.size(); ++i) {
    const Eigen::Vector3f mid = 0.5f * (p[i - 1] + p[i]);
    if (head(mid) >= floor) continue;
    p.insert(p.begin() + static_cast<std::ptrdiff_t>(i), head.push_out(mid, context.min_clearance));
    ++i;  // the halves are not checked again: each is a quarter of the sag
  }
}

}  // namespace

std::vector<int> detail_guides(const std::vector<StrandDetail>& details, const DetailContext& context) {
  std::vector<int> out;
  for (const auto& d : details)
    if (std::holds_alternative<ClumpDetail>(d.shape)) {
      const std::vector<int> g = clump_guides(d, context);
      out.insert(out.end(), g.begin(), g.end());
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Strands apply_strand_detail(const Strands& strands, const std::vector<StrandDetail>& details,
                            const DetailContext& context) {
  const std::string fn = "hair_sketch::apply_strand_detail()";
  const std::size_t whole = context.root_vertex.size();
  if (context.strand_index.empty() ? whole != static_cast<std::size_t>(strands.count())
                                   : context.strand_index.size() != static_cast<std::size_t>(strands.count()))
    throw InvalidArgument(fn + ": the detail context is for " +
                          std::to_string(context.strand_index.empty() ? whole : context.strand_index.size()) +
                          " strands, not " + std::to_string(strands.count()));
  for (std::size_t i = 0; i < context.strand_index.size(); ++i)
    if (context.strand_index[i] < 0 || static_cast<std::size_t>(context.strand_index[i]) >= whole ||
        (i > 0 && context.strand_index[i] <= context.strand_index[i - 1]))
      throw InvalidArgument(fn + ": the detail context's strand indices must increase within the " +
                            std::to_string(whole) + " strands");
  for (const auto& d : details) check_detail(d, std::numeric_limits<int>::max(), fn);
  if (details.empty()) return strands;
  std::vector<detail::Polyline> polylines = unpack(strands);
  for (const auto& d : details) apply_one(d, polylines, context);
  if (context.clearance) {
    const auto n = static_cast<std::ptrdiff_t>(polylines.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (std::ptrdiff_t s = 0; s < n; ++s) keep_segments_outside(polylines[s], context);
  }
  return pack(polylines);
}

}  // namespace lapis::hair_sketch
