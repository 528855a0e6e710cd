// Local detail in the field (thesis §4.7, Eq. 4.1 with δᵢ = Δ(tᵉᵢ)): the solved field is the
// exact minimizer of the rewritten energy, carries the example's waves away from the
// constraints, and is the thesis' smooth field when the detail is off.
#include <doctest/doctest.h>

#include <cmath>

#include "fixture.h"
#include "lapis/core/error.h"
#include "lapis/hair_field/grid_operators.h"
#include "lapis/hair_sketch/field_detail.h"
#include "lapis/hair_sketch/style_field.h"

using namespace hair_test;

namespace {

// Two stream curves down the back of the head, at azimuths ±0.35.
std::vector<StylePrimitive> back_curves() {
  std::vector<StylePrimitive> out;
  for (const double x : {-0.35, 0.35}) {
    StreamCurve c;
    for (int i = 0; i <= 20; ++i) {
      const double a = 0.25 + 1.6 * i / 20.0;
      c.points.emplace_back(x, 1.25 * std::cos(a), -1.25 * std::sin(a));
    }
    out.push_back({c});
  }
  return out;
}

FieldDetailOptions waves() {
  FieldDetailOptions o;
  o.amplitude = 0.5;
  o.wavelength = 0.6;
  return o;
}

}  // namespace

TEST_CASE("hair_sketch: the field with detail minimizes Eq. 4.1 with the example's differential coordinates") {
  const Head& head = bundled_head();
  const Grid g = small_grid(8000);
  StyleField detailed(head, g, FieldMethod::Thesis, {}, waves());
  detailed.update(back_curves());
  const Field example = wavy_example_field(g, head.center, waves());
  // The normal equations of E = ||D t − D tᵉ||² + ω² Σ ||tᵢ − cᵢ||²:
  //   (DᵀD + ω² W) t = DᵀD tᵉ + ω² W c.
  const ConstraintSet set = style_constraints(back_curves(), g, head);
  Eigen::VectorXd weights = Eigen::VectorXd::Zero(g.num_nodes());
  Field targets = Field::Zero(g.num_nodes(), 3);
  for (const Constraint& c : set.items()) {
    weights[c.node] = 100.0 * 100.0;
    targets.row(c.node) = c.direction.transpose();
  }
  Field lhs, smooth_part;
  apply_normal_operator(g, weights, detailed.field(), lhs);
  apply_normal_operator(g, Eigen::VectorXd::Zero(g.num_nodes()), example, smooth_part);
  const Field rhs = smooth_part + weights.asDiagonal() * targets;
  CHECK((lhs - rhs).norm() <= 1e-8 * rhs.norm());
}

TEST_CASE("hair_sketch: field detail reproduces the example's local variation away from the constraints") {
  const Head& head = bundled_head();
  const Grid g = small_grid(12000);
  StyleField plain(head, g, FieldMethod::Thesis);
  StyleField detailed(head, g, FieldMethod::Thesis, {}, waves());
  plain.update(back_curves());
  detailed.update(back_curves());
  const Field example = wavy_example_field(g, head.center, waves());
  // What δᵢ carries is the example's differential coordinates: compare Δ(t) with Δ(tᵉ), and
  // the field itself, on nodes at least three cells from every constrained node.
  const SparseMatrix D = laplacian_matrix(g);
  const Field delta = D * example, solved = D * detailed.field();
  std::vector<Eigen::Vector3d> constrained;
  for (const Constraint& c : plain.constraints().items()) constrained.push_back(g.position(c.node));
  double dot = 0, solved2 = 0, delta2 = 0, plain_dot = 0, plain2 = 0;
  int counted = 0;
  const Field smooth = D * plain.field();
  for (int i = 0; i < g.num_nodes(); ++i) {
    const Eigen::Vector3d p = g.position(i);
    bool far = true;
    for (const auto& q : constrained) far = far && (p - q).norm() > 3 * g.spacing;
    if (!far) continue;
    dot += solved.row(i).dot(delta.row(i));
    solved2 += solved.row(i).squaredNorm();
    delta2 += delta.row(i).squaredNorm();
    plain_dot += smooth.row(i).dot(delta.row(i));
    plain2 += smooth.row(i).squaredNorm();
    ++counted;
  }
  REQUIRE(counted > 1000);
  const double cosine = dot / std::sqrt(solved2 * delta2), plain_cosine = plain_dot / std::sqrt(plain2 * delta2);
  MESSAGE("cosine of the field's Laplacian with the example's over " << counted << " nodes: " << cosine
                                                                     << " (without detail: " << plain_cosine << ")");
  CHECK(cosine > 0.95);
  CHECK(std::abs(plain_cosine) < 0.2);  // the smooth field has none of it
  // At the constraints the field still meets them.
  for (const Constraint& c : plain.constraints().items())
    CHECK((detailed.field().row(c.node).transpose() - c.direction).norm() < 0.05);
}

TEST_CASE("hair_sketch: field detail off is the smooth field, bit for bit; bad options are typed errors") {
  const Head& head = bundled_head();
  const Grid g = small_grid(6000);
  StyleField plain(head, g, FieldMethod::Thesis), off(head, g, FieldMethod::Thesis, {}, FieldDetailOptions{});
  plain.update(back_curves());
  off.update(back_curves());
  CHECK(plain.field() == off.field());
  FieldDetailOptions bad;
  bad.amplitude = NAN;
  CHECK_THROWS_WITH_AS(StyleField(head, g, FieldMethod::Thesis, {}, bad), doctest::Contains("amplitude"),
                       lapis::InvalidArgument);
  bad.amplitude = 0.1;
  bad.wavelength = 0;
  CHECK_THROWS_WITH_AS(wavy_example_field(g, head.center, bad), doctest::Contains("wavelength"),
                       lapis::InvalidArgument);
}
