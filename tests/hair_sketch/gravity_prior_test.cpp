// The gravity prior: hair far from a lone curve falls instead of following it sideways, while
// the curve still decides near itself; the prior's own constraints.
#include <doctest/doctest.h>

#include <cmath>

#include "fixture.h"
#include "lapis/core/error.h"
#include "lapis/hair_sketch/gravity_prior.h"
#include "lapis/hair_sketch/stream_curve.h"
#include "lapis/hair_sketch/style_field.h"

using namespace hair_test;

namespace {

// One stream curve along the left side of the head, level, from the temple to the back: the
// lone curve that, without the prior, turns all the hair into a sideways sheet.
StylePrimitive level_side_curve() {
  const Head& head = bundled_head();
  StreamCurve c;
  for (int i = 0; i <= 16; ++i) {
    const double a = 0.5 * i / 16.0;  // x = −1 side, from the front toward the back
    const Eigen::Vector3d dir(-std::cos(a), 0.25, -std::sin(a));
    const Eigen::Vector3d on_head = head.closest(head.center + 3 * dir).second;
    c.points.push_back(head.center + 1.15 * (on_head - head.center));  // a little off the scalp
  }
  StylePrimitive p;
  p.shape = c;
  return p;
}

// Mean over strands rooted at x > 0.3 (the side away from the curve) of how much their first
// unit of length goes down: (end − root)·(−y) / |end − root|.
double fall_of_far_side(const Strands& st, const std::vector<Eigen::Vector3d>& roots) {
  double sum = 0;
  int n = 0;
  for (int s = 0; s < st.count(); ++s) {
    if (roots[static_cast<size_t>(s)].x() < 0.3) continue;
    const int a = st.offsets[static_cast<size_t>(s)], b = st.offsets[static_cast<size_t>(s) + 1];
    double walked = 0;
    int i = a;
    while (i + 1 < b && walked < 1.0)
      walked += (st.points[static_cast<size_t>(i) + 1] - st.points[static_cast<size_t>(i)]).norm(), ++i;
    const Eigen::Vector3d move = (st.points[static_cast<size_t>(i)] - st.points[static_cast<size_t>(a)]).cast<double>();
    if (move.norm() < 0.2) continue;
    sum += -move.y() / move.norm();
    ++n;
  }
  REQUIRE(n > 100);
  return sum / n;
}

struct Grown {
  Strands strands;
  std::vector<Eigen::Vector3d> roots;
  Field field;
  ConstraintSet constraints;
};

Grown grow_with(double prior_strength) {
  const Head& head = bundled_head();
  const Grid g = small_grid();
  GravityPriorOptions prior;
  prior.strength = prior_strength;
  StyleField field(head, g, FieldMethod::Thesis, {}, {}, prior);
  field.update({level_side_curve()});
  RootOptions ro;
  ro.count = 1500;
  Grown out;
  out.roots = sample_roots(head, ro);
  out.field = field.field();
  out.constraints = field.constraints();
  out.strands = grow_strands(SampledField(g, out.field), out.roots);
  return out;
}

}  // namespace

TEST_CASE("gravity prior: with one level curve, hair away from it falls; without, it follows the curve sideways") {
  const Grown thesis = grow_with(0), prior = grow_with(0.3);
  const double fall_thesis = fall_of_far_side(thesis.strands, thesis.roots);
  const double fall_prior = fall_of_far_side(prior.strands, prior.roots);
  MESSAGE("far side: mean downward share of the first unit of hair " << fall_thesis << " (thesis) -> " << fall_prior
                                                                     << " (prior)");
  CHECK(fall_thesis < 0.35);  // the sheet the prior is for
  CHECK(fall_prior > 0.6);
  // Where the user sketched, the user decides: on the curve's nodes the field is the thesis'
  // field (whose own agreement with the curve is that of Eq. 4.1's soft constraints).
  const Grid g = small_grid();
  const auto curve = std::get<StreamCurve>(level_side_curve().shape).constraints(g);
  REQUIRE(curve.size() > 10);
  double worst = 1;
  for (const auto& c : curve)
    worst = std::min(worst, cosine(prior.field.row(c.node).transpose(), thesis.field.row(c.node).transpose()));
  MESSAGE("on the curve's nodes, the least cosine between the fields with and without the prior: " << worst);
  CHECK(worst > 0.999);
}

TEST_CASE("gravity prior: constraints outside the head, out of the scalp near it and down away from it") {
  const Head& head = bundled_head();
  const Grid g = small_grid();
  GravityPriorOptions o;
  o.strength = 0.3;
  const auto prior = gravity_prior_constraints(head, g, o);
  REQUIRE(prior.size() > 100);
  CHECK(static_cast<double>(prior.size()) < 1.2 * static_cast<double>(g.num_nodes()) / 27);  // one per 3³ block
  for (const auto& c : prior) {
    CHECK_FALSE(head.inside(g.position(c.node)));
    CHECK(c.direction.norm() <= 0.3 + 1e-12);
  }
  // Just above the crown: along the outward normal; far from the head: straight down.
  const Eigen::Vector3d crown = head.closest(head.center + Eigen::Vector3d(0, 5, 0)).second;
  const auto [normal, point] = head.closest(crown + Eigen::Vector3d(0, 0.01, 0));
  CHECK(gravity_prior_direction(head, point + 0.01 * normal, o).dot(normal) > 0.9);
  const Eigen::Vector3d far = head.center + Eigen::Vector3d(2.5, -1.0, 0);
  CHECK((gravity_prior_direction(head, far, o) - Eigen::Vector3d(0, -1, 0)).norm() < 1e-12);
  // With the user's constraints, the prior only fills free nodes: on a shared node the user's
  // target stays as it is (not averaged), and the user's other nodes are kept.
  const int free_node = prior[0].node + 1;  // the prior takes one node in every `stride` along x
  const ConstraintSet user =
      ConstraintSet::from({{prior[0].node, Eigen::Vector3d(1, 0, 0)}, {free_node, Eigen::Vector3d(0, 0, 1)}});
  const ConstraintSet both = with_prior(user, prior);
  CHECK(both.size() == static_cast<int>(prior.size()) + 1);
  CHECK(*both.find(prior[0].node) == Eigen::Vector3d(1, 0, 0));
  CHECK(*both.find(free_node) == Eigen::Vector3d(0, 0, 1));
}

TEST_CASE("gravity prior: off adds nothing; bad options are named") {
  const Head& head = bundled_head();
  const Grid g = small_grid();
  CHECK(gravity_prior_constraints(head, g, {}).empty());
  GravityPriorOptions o;
  o.strength = -1;
  CHECK_THROWS_WITH_AS(gravity_prior_constraints(head, g, o), doctest::Contains("strength"), lapis::InvalidArgument);
  o = {};
  o.stride = 0;
  CHECK_THROWS_WITH_AS(gravity_prior_constraints(head, g, o), doctest::Contains("stride"), lapis::InvalidArgument);
  o = {};
  o.down = Eigen::Vector3d::Zero();
  CHECK_THROWS_WITH_AS(gravity_prior_constraints(head, g, o), doctest::Contains("down"), lapis::InvalidArgument);
}

TEST_CASE("gravity prior: no prior node within its clearance of a sketched node") {
  const Head& head = bundled_head();
  const Grid g = small_grid();
  GravityPriorOptions o;
  o.strength = 0.3;
  const auto prior = gravity_prior_constraints(head, g, o);
  const auto curve = std::get<StreamCurve>(level_side_curve().shape).constraints(g);
  const ConstraintSet sketched = ConstraintSet::from(curve);
  const auto kept = prior_away_from(prior, sketched, g, o.clearance);
  CHECK(kept.size() < prior.size());
  size_t far = 0;  // prior nodes farther than the clearance from every curve node: all kept
  for (const auto& p : prior) {
    const auto a = g.coords(p.node);
    int nearest = 1 << 30;
    for (const auto& c : curve) {
      const auto b = g.coords(c.node);
      nearest = std::min(nearest, std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])}));
    }
    const bool is_kept = std::any_of(kept.begin(), kept.end(), [&](const auto& k) { return k.node == p.node; });
    CHECK(is_kept == (nearest > o.clearance));
    far += nearest > o.clearance;
  }
  CHECK(kept.size() == far);
}
