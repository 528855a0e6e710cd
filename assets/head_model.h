// The bundled head as an implicit surface: a signed distance (negative inside) built from smooth
// unions and subtractions of ellipsoids, capsules and cones, so that a bust with shoulders,
// which no star-shaped r(direction) can describe, is one closed smooth surface of genus 0.
// Units: y up, face towards +z, crown at y = 1, chin near y = -1, cranium centred near the
// origin (where the earlier star-shaped head had it, so strokes on its scalp still land).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace head_model {

using Vec = Eigen::Vector3d;

// Polynomial smooth minimum (blend width k): C1, and equal to min beyond |a - b| > k, so a
// blend stays local to the seam instead of inflating the whole part as an exponential one does.
inline double smin(double a, double b, double k) {
  const double h = std::max(k - std::abs(a - b), 0.0) / k;
  return std::min(a, b) - 0.25 * h * h * k;
}
inline double smax(double a, double b, double k) { return -smin(-a, -b, k); }
// a with b carved out, the carving's rim rounded over width k.
inline double carve(double a, double b, double k) { return smax(a, -b, k); }

// Ellipsoid distance bound (first-order, exact on the axes): good enough for blends a few
// hundredths wide, unlike |p/r| - 1, whose scale varies with the radii.
inline double ellipsoid(const Vec& p, const Vec& c, const Vec& r) {
  const Vec q = p - c;
  const double k0 = q.cwiseQuotient(r).norm();
  const double k1 = q.cwiseQuotient(r.cwiseProduct(r)).norm();
  return k1 > 1e-12 ? k0 * (k0 - 1.0) / k1 : -r.minCoeff();
}

inline double capsule(const Vec& p, const Vec& a, const Vec& b, double r) {
  const Vec ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - a - t * ab).norm() - r;
}

// A cone between spheres (a, ra) and (b, rb) whose sides are tangent to both (Quilez's exact
// round cone): the nose bridge and the neck taper without a crease.
inline double round_cone(const Vec& p, const Vec& a, const Vec& b, double ra, double rb) {
  const Vec ba = b - a, pa = p - a;
  const double l2 = ba.squaredNorm(), rr = ra - rb, a2 = l2 - rr * rr, il2 = 1.0 / l2;
  const double y = pa.dot(ba), z = y - l2;
  const double x2 = (pa * l2 - ba * y).squaredNorm(), y2 = y * y * l2, z2 = z * z * l2;
  const double k = (rr > 0 ? 1.0 : -1.0) * rr * rr * x2;
  if ((z > 0 ? 1.0 : -1.0) * a2 * z2 > k) return std::sqrt(x2 + z2) * il2 - rb;
  if ((y > 0 ? 1.0 : -1.0) * a2 * y2 < k) return std::sqrt(x2 + y2) * il2 - ra;
  return (std::sqrt(x2 * a2 * il2) + y * rr) * il2 - ra;
}

// Mirrors x so that one call models both sides of the face.
inline Vec mirror_x(Vec p) {
  p.x() = std::abs(p.x());
  return p;
}

// Cranium, brow, cheekbones and the mass of the face and jaw, before the carved details.
inline double skull(const Vec& p) {
  const Vec m = mirror_x(p);
  double d = ellipsoid(p, {0, 0.02, -0.05}, {0.78, 0.98, 0.98});                   // cranium
  d = smin(d, ellipsoid(p, {0, 0.30, 0.30}, {0.62, 0.48, 0.64}), 0.10);            // forehead
  d = smin(d, ellipsoid(p, {0, -0.33, 0.30}, {0.57, 0.55, 0.58}), 0.25);           // mid face
  d = smin(d, ellipsoid(p, {0, -0.62, 0.34}, {0.46, 0.38, 0.50}), 0.20);           // mouth and lower face
  d = smin(d, capsule(m, {0.54, -0.42, -0.14}, {0.22, -0.88, 0.56}, 0.13), 0.18);  // jaw line
  d = smin(d, ellipsoid(p, {0, -0.86, 0.62}, {0.23, 0.16, 0.21}), 0.12);           // chin
  d = smin(d, ellipsoid(m, {0.47, -0.12, 0.55}, {0.22, 0.14, 0.25}), 0.20);        // cheekbones
  d = smin(d, ellipsoid(m, {0.38, -0.36, 0.46}, {0.24, 0.30, 0.32}), 0.20);        // cheeks
  d = smin(d, ellipsoid(m, {0.27, 0.12, 0.80}, {0.21, 0.07, 0.12}), 0.10);         // brow ridges
  return d;
}

// Eye sockets carved below the brow, then eyeballs set back in them (the lids are the blend).
inline double eyes(const Vec& p, double d) {
  const Vec m = mirror_x(p);
  d = carve(d, ellipsoid(m, {0.29, -0.03, 0.86}, {0.16, 0.10, 0.15}), 0.14);
  return smin(d, (m - Vec(0.29, -0.035, 0.66)).norm() - 0.12, 0.05);
}

// Bridge, tip and wings of the nose.
inline double nose(const Vec& p) {
  const Vec m = mirror_x(p);
  double d = round_cone(p, {0, 0.04, 0.86}, {0, -0.36, 1.08}, 0.05, 0.075);
  // The body under the bridge, down to the face: with the wings, a bridge standing free of
  // the face would close two tunnels beneath it.
  d = smin(d, ellipsoid(p, {0, -0.24, 0.90}, {0.085, 0.22, 0.11}), 0.05);
  d = smin(d, (p - Vec(0, -0.39, 1.08)).norm() - 0.09, 0.05);  // tip
  // Wings reach back into the cheeks: wings touching only the tip would leave a tunnel.
  d = smin(d, ellipsoid(m, {0.10, -0.42, 0.92}, {0.075, 0.07, 0.13}), 0.05);
  return d;
}

// Upper and lower lip, parted by a groove wide enough for the mesh to follow without a crease.
inline double lips(const Vec& p) {
  double d = ellipsoid(p, {0, -0.625, 0.85}, {0.17, 0.06, 0.10});
  d = smin(d, ellipsoid(p, {0, -0.725, 0.835}, {0.15, 0.065, 0.095}), 0.03);
  return carve(d, capsule(p, {-0.12, -0.675, 0.955}, {0.12, -0.675, 0.955}, 0.03), 0.04);
}

// A flat shell beside the temple with a hollow bowl. Its root fills the whole front and middle
// of the shell's inner side: an ear touching the head only at its top and lobe would leave a
// tunnel behind it, a handle in a surface that must have genus 0.
inline double ears(const Vec& p) {
  const Vec m = mirror_x(p);
  double d = ellipsoid(m, {0.80, -0.13, -0.08}, {0.075, 0.28, 0.17});
  d = smin(d, ellipsoid(m, {0.74, -0.14, -0.05}, {0.08, 0.25, 0.13}), 0.05);
  return carve(d, ellipsoid(m, {0.875, -0.15, -0.06}, {0.04, 0.15, 0.09}), 0.03);
}

// Neck, shoulders and chest, cut flat at the bottom and the arms like a sculptor's bust.
inline double bust(const Vec& p) {
  // The neck leans forward from its base, as a standing person's does.
  double d = round_cone(p, {0, -0.35, -0.12}, {0, -1.75, -0.22}, 0.43, 0.47);  // neck
  // Shoulders slope down from the base of the neck (the trapezius) to rounded tips.
  const double shoulders = capsule(mirror_x(p), {0.25, -1.62, -0.14}, {1.12, -1.92, -0.12}, 0.33);
  const double chest = ellipsoid(p, {0, -2.30, 0.0}, {1.25, 0.62, 0.74});
  d = smin(d, smin(shoulders, chest, 0.30), 0.35);
  d = smax(d, -2.45 - p.y(), 0.08);              // the base
  return smax(d, std::abs(p.x()) - 1.42, 0.08);  // the arms' cut
}

inline double head(const Vec& p) {
  double d = eyes(p, skull(p));
  d = smin(d, nose(p), 0.08);
  d = smin(d, lips(p), 0.06);
  d = smin(d, ears(p), 0.09);
  return smin(d, bust(p), 0.25);
}

// The ears' shells alone, for keeping them out of the scalp.
inline double ear_distance(const Vec& p) { return ellipsoid(mirror_x(p), {0.80, -0.13, -0.08}, {0.075, 0.28, 0.17}); }

// The cranium ellipsoid alone, for telling the hair-bearing cap from the face and neck.
inline double cranium_distance(const Vec& p) { return ellipsoid(p, {0, 0.02, -0.05}, {0.78, 0.98, 0.98}); }

}  // namespace head_model
