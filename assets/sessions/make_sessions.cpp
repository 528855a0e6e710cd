// Generates the example sessions assets/sessions/{smooth,parting,ponytails}.json, which
// recreate thesis Figs. 4.6–4.8 on the bundled head, half_up.json with Fig. 4.1's mix of
// primitives, and {curly_bob,wavy_long}.json, which add
// strand detail (§4.7) to the smooth style: strokes are drawn by projecting 3D
// paths over the head with orbit-style cameras, interpreted exactly as the app would, and
// recorded in the session. Deterministic; run by hand, outputs are committed:
//   lapis_make_sessions <source dir>
// Then regenerate each report with `lapis hair --session X.json --out-hair /tmp/x.hair
// --report X.report.json`.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/stroke_commands.h"
#include "lapis/hair_sketch/style_field.h"

using namespace lapis::hair_sketch;
using namespace lapis::hair_field;
using lapis::geometry::CameraMatrices;

namespace {

CameraMatrices look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                       const Eigen::Vector3d& up = Eigen::Vector3d::UnitY()) {
  return lapis::geometry::look_at_camera(eye, target, up);
}

struct Drawer {
  const Head& head;
  Document doc;
  Grid grid;

  Eigen::Vector3d on_head(const Eigen::Vector3d& d) const {
    const Eigen::Vector3d dir = d.normalized();
    return head.bvh->intersect(head.center + 5 * dir, -dir)->point;
  }
  Stroke project(const CameraMatrices& c, const std::vector<Eigen::Vector3d>& pts) const {
    Stroke s;
    for (const auto& p : pts) s.push_back(lapis::geometry::project(c, p).head<2>());
    return s;
  }
  // Over the head from polar angle a0 to a1 (from +y) at azimuth phi (0 = face, +z), then
  // `hang` pixels straight down the screen: hair falling past the scalp's edge.
  Stroke over_head(const CameraMatrices& c, double phi, double a0, double a1, double hang) const {
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i <= 24; ++i) {
      const double a = a0 + (a1 - a0) * i / 24;
      pts.push_back(on_head({std::sin(a) * std::sin(phi), std::cos(a), std::sin(a) * std::cos(phi)}));
    }
    Stroke s = project(c, pts);
    for (int k = 1; k <= 10; ++k) s.push_back(s.back() + Eigen::Vector2d(0, hang / 10));
    return s;
  }
  // From the front hairline (polar angle a0, azimuth phi0) across the temple to the side of
  // the head (a1, phi1), then `hang` pixels down: hair swept off the face, which would
  // otherwise fall straight over it (nothing else pushes the front roots sideways).
  Stroke swept_aside(const CameraMatrices& c, double a0, double phi0, double a1, double phi1, double hang) const {
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i <= 24; ++i) {
      const double t = static_cast<double>(i) / 24, a = a0 + (a1 - a0) * t, phi = phi0 + (phi1 - phi0) * t;
      pts.push_back(on_head({std::sin(a) * std::sin(phi), std::cos(a), std::sin(a) * std::cos(phi)}));
    }
    Stroke s = project(c, pts);
    for (int k = 1; k <= 10; ++k) s.push_back(s.back() + Eigen::Vector2d(0, hang / 10));
    return s;
  }
  CameraMatrices facing(double phi, double elevation = 0.5) const {
    const Eigen::Vector3d eye(5 * std::sin(phi), 5 * elevation, 5 * std::cos(phi));
    return look_at(eye, {0, 0.2, 0});
  }
  // A stream curve drawn from the camera facing azimuth `view`: swept_aside / over_head.
  void sweep(double view, double a0, double phi0, double a1, double phi1, double hang) {
    add(StrokeAction::StreamCurve, facing(view), {swept_aside(facing(view), a0, phi0, a1, phi1, hang)});
  }
  void fall(double phi, double a0, double a1, double hang) {
    add(StrokeAction::StreamCurve, facing(phi), {over_head(facing(phi), phi, a0, a1, hang)});
  }
  // A ponytail drawn from camera c along a 17-point spine: the cross section round its seventh
  // point (drawn with radius 0.25, read as 0.155) and two profiles that narrow down the tail.
  void add_ponytail(const CameraMatrices& c, const std::vector<Eigen::Vector3d>& spine) {
    constexpr double kRadius = 0.25, kPi = std::numbers::pi;
    std::vector<Eigen::Vector3d> loop, pa, pb;
    for (int k = 0; k <= 24; ++k) {
      const double t = 2 * kPi * k / 24;
      loop.push_back(spine[6] + kRadius * Eigen::Vector3d(std::cos(t), 0.35 * std::sin(t), 0));
    }
    for (int i = 6; i <= 17; ++i) {
      const double ri = kRadius * (1.3 - 0.05 * (i - 6));
      pa.push_back(spine[static_cast<size_t>(i)] + Eigen::Vector3d(ri, 0, 0));
      pb.push_back(spine[static_cast<size_t>(i)] - Eigen::Vector3d(ri, 0, 0));
    }
    add(StrokeAction::Ponytail, c, {project(c, spine), project(c, loop), project(c, pa), project(c, pb)});
  }
  void add(StrokeAction a, const CameraMatrices& c, std::vector<Stroke> strokes, int target = -1) {
    RecordedStroke r;
    r.action = a;
    r.camera = c;
    r.strokes = std::move(strokes);
    r.target = target;
    apply_stroke(doc, r, head, grid);
  }
};

Drawer start(const Head& head, double unknowns, double gravity_prior) {
  Hairstyle h;
  h.settings.head_mesh = "../head.obj";
  h.settings.scalp_mask = "../head_scalp.txt";
  h.settings.grid.target_unknowns = unknowns;
  h.settings.gravity_prior.strength = gravity_prior;
  h.settings.field_method = FieldMethod::Auto;  // the thesis path to ~10K unknowns, multigrid beyond
  h.settings.roots.count = 2000;
  h.camera = look_at({0, 2.5, 5}, {0, 0.2, 0});
  return {head, Document(h), hairstyle_grid(head, h.settings)};
}

constexpr double kPi = std::numbers::pi;

// The front hair on one side swept off the face to behind the ear: from the front of the
// scalp, and from the hairline itself (over the brow's relief, hair there would fall on the
// face). At §4.6's 25K unknowns a curve steers fewer of the roots around it than at 8K, so two
// sweep the hairline, between the temple and the forehead.
void sweep_fringe(Drawer& d, int side) {
  const double p = side * 0.3 * kPi;
  d.sweep(p, 0.45, side * 0.06 * kPi, 1.25, side * 0.55 * kPi, 90);
  d.sweep(p, 0.8, side * 0.04 * kPi, 1.35, side * 0.5 * kPi, 90);
  d.sweep(p, 0.95, side * 0.12 * kPi, 1.45, side * 0.5 * kPi, 90);
}

// Fig. 4.6: a smooth style from ten stream curves, crown to shoulders all around but the face.
void smooth(Drawer& d) {
  for (int k = 0; k < 10; ++k) {
    const double phi = 0.35 * kPi + 1.3 * kPi * k / 9;
    d.fall(phi, 0.25, 1.45, 120);
  }
  for (int side : {-1, 1}) {
    sweep_fringe(d, side);
    // One more from the middle of the forehead.
    d.sweep(side * 0.3 * kPi, 0.62, side * 0.01 * kPi, 1.3, side * 0.52 * kPi, 90);
  }
  // The middle of the hairline combed back: between the two sweeps the field has no side to
  // take, and the hair there would fall straight over the face.
  for (double phi : {-0.08 * kPi, 0.0, 0.08 * kPi}) d.sweep(0.25 * kPi, 0.95, phi, 0.3, phi, 0);
}

// Fig. 4.7: a parting from the forehead to the crown, seven stream curves flowing away from it.
void parting(Drawer& d) {
  const CameraMatrices top = look_at({0, 5, 0.3}, {0, 0, 0}, {0, 0, -1});
  std::vector<Eigen::Vector3d> line;
  for (int i = 0; i <= 20; ++i) {
    const double a = 0.55 - 0.75 * i / 20;  // polar angle towards the face, then past the top
    line.push_back(d.on_head({0.18, std::cos(a), std::sin(a)}));
  }
  d.add(StrokeAction::DividingCurve, top, {d.project(top, line)});
  for (int side : {-1, 1})
    for (double phi : {0.25 * kPi, 0.5 * kPi, 0.75 * kPi}) d.fall(side * phi, 0.3, 1.5, 110);
  d.fall(kPi, 0.3, 1.5, 140);
  for (int side : {-1, 1}) sweep_fringe(d, side);
  // Tilt the parting's start: hair on the right side sweeps slightly back.
  const auto& dc = std::get<DividingCurve>(d.doc.style().primitives[0].shape);
  const Eigen::Vector3d foot = dc.points[2], x0 = dividing_side_axis(dc, d.head, 0.1);
  std::vector<Eigen::Vector3d> pts;
  for (int k = 1; k <= 6; ++k)
    pts.push_back(d.on_head(foot + 0.06 * k * x0 - 0.025 * k * Eigen::Vector3d::UnitZ() - d.head.center));
  d.add(StrokeAction::Tilt, top, {d.project(top, pts)}, 0);
}

// Fig. 4.8: two ponytails at the back of the head and ten stream curves leading to them (the
// front and top hair swept back over the temples, the back hair parted down the middle and
// drawn sideways to the tails). 50K unknowns, as §4.6 asks for ponytails: a grid cell (0.137
// over the head and shoulders' box) must stay narrower than the cross-section (r 0.155), or no
// strand passes through C1 (a 12K grid caught none; at 30K the cell is 0.163).
void ponytails(Drawer& d) {
  for (double phi : {0.6 * kPi, -0.6 * kPi}) d.fall(phi, 0.2, 1.0, 30);
  for (int side : {-1, 1}) {  // the front and top hair swept back over the temples to the tails
    const double p = side * 0.35 * kPi;
    d.sweep(p, 0.45, side * 0.06 * kPi, 1.1, side * 0.72 * kPi, 20);
    d.sweep(p, 0.22, side * 0.12 * kPi, 0.95, side * 0.78 * kPi, 20);
  }
  for (int side : {-1, 1}) {  // the back hair: from the crown and from the nape to the tails
    const double p = side * 0.85 * kPi;
    d.sweep(p, 0.3, side * 0.97 * kPi, 0.9, side * 0.74 * kPi, 0);
    d.sweep(p, 1.75, side * 0.97 * kPi, 1.1, side * 0.74 * kPi, 0);
  }
  const CameraMatrices back = look_at({0, 0.8, -5}, {0, 0.2, 0});
  for (int side : {-1, 1}) {
    // Spine: from the scalp behind the ear, out and down.
    std::vector<Eigen::Vector3d> spine;
    const double phi = kPi - side * 0.3 * kPi;
    for (int i = 0; i <= 4; ++i) {
      const double a = 0.9 + 0.05 * i;
      spine.push_back(d.on_head({std::sin(a) * std::sin(phi), std::cos(a), std::sin(a) * std::cos(phi)}));
    }
    const Eigen::Vector3d out = spine.back() + 0.25 * Eigen::Vector3d(side * 0.8, 0, -0.6);
    for (int i = 0; i <= 12; ++i) spine.push_back(out + Eigen::Vector3d(side * 0.05 * i, -0.12 * i, -0.02 * i));
    d.add_ponytail(back, spine);
  }
}

// Fig. 4.1's mix of primitives (eleven stream curves, four dividing curves, one ponytail) as a
// half-up style: four dividing curves run round the head above the ears and across the back,
// the hair above them is drawn back into one ponytail behind the crown, the hair below falls.
void half_up(Drawer& d) {
  // The dividing curves, each drawn from the side it runs along: from azimuth phi0 to phi1
  // (in half turns) and polar angle a0 to a1, on the side's half of the head.
  const auto dividing = [&](int side, double view, double phi0, double phi1, double a0, double a1) {
    std::vector<Eigen::Vector3d> line;
    for (int i = 0; i <= 16; ++i) {
      const double t = static_cast<double>(i) / 16, phi = side * (phi0 + (phi1 - phi0) * t) * kPi;
      const double a = a0 + (a1 - a0) * t;
      line.push_back(d.on_head({std::sin(a) * std::sin(phi), std::cos(a), std::sin(a) * std::cos(phi)}));
    }
    const CameraMatrices c = d.facing(side * view * kPi);
    d.add(StrokeAction::DividingCurve, c, {d.project(c, line)});
  };
  for (int side : {-1, 1}) dividing(side, 0.55, 0.22, 0.72, 1.05, 1.1);  // above the ears
  for (int side : {-1, 1}) dividing(side, 0.88, 0.74, 0.98, 1.1, 1.12);  // across the back
  // Above them: four curves from the front and the temples back to the tail.
  for (int side : {-1, 1}) {
    const double p = side * 0.45 * kPi;
    d.sweep(p, 0.5, side * 0.08 * kPi, 0.75, side * 0.9 * kPi, 0);
    d.sweep(p, 0.85, side * 0.25 * kPi, 0.85, side * 0.85 * kPi, 0);
  }
  // Below them: the sides and the back fall, the hairline is swept off the face.
  for (int side : {-1, 1}) {
    for (double phi : {0.5 * kPi, 0.8 * kPi}) {
      const double p = side * phi;
      d.fall(p, 1.25, 1.6, 140);
    }
    const double p = side * 0.3 * kPi;
    d.sweep(p, 0.95, side * 0.12 * kPi, 1.45, side * 0.5 * kPi, 90);
  }
  d.fall(kPi, 1.3, 1.6, 140);
  // The ponytail, from behind: its spine leaves the scalp behind the crown and falls.
  const CameraMatrices back = look_at({0, 0.8, -5}, {0, 0.2, 0});
  std::vector<Eigen::Vector3d> spine;
  for (int i = 0; i <= 4; ++i) spine.push_back(d.on_head({0, std::cos(0.8 + 0.04 * i), -std::sin(0.8 + 0.04 * i)}));
  const Eigen::Vector3d out = spine.back() + 0.25 * Eigen::Vector3d(0, 0, -1);
  for (int i = 0; i <= 12; ++i) spine.push_back(out + Eigen::Vector3d(0, -0.12 * i, -0.03 * i));
  d.add_ponytail(back, spine);
}

StrandDetail with_seed(decltype(StrandDetail::shape) shape, std::uint32_t seed) {
  StrandDetail d;
  d.shape = std::move(shape);
  d.seed = seed;
  return d;
}

// The smooth style cut level with the jaw by a line drawn from a level side view, varied in
// length, gathered into clumps and curled into ringlets that widen toward the tips.
void curly_bob(Drawer& d) {
  smooth(d);
  CutDetail cut;
  cut.camera = look_at({6, -0.4, 0}, {0, -0.4, 0});
  const double y = lapis::geometry::project(cut.camera, Eigen::Vector3d(0, -0.8, 0)).y();
  cut.line = {Eigen::Vector2d(-100, y), Eigen::Vector2d(cut.camera.viewport[2] + 100, y)};
  ClumpDetail clumps;
  clumps.clumps = 160;
  clumps.strength = 0.55;
  clumps.profile = 1.2;
  CurlDetail ringlets;
  ringlets.frequency = 6;
  ringlets.radius = 0.045;
  ringlets.radius_growth = 0.4;
  d.doc.execute(
      {"add details",
       SetDetails{{with_seed(LengthDetail{0.12}, 1), with_seed(cut, 2), with_seed(clumps, 3), with_seed(ringlets, 4)}},
       std::nullopt});
}

// The smooth style in long, loose waves: neighbouring strands wave together (little phase
// jitter) in soft clumps, with a trace of frizz.
void wavy_long(Drawer& d) {
  smooth(d);
  ClumpDetail clumps;
  clumps.clumps = 220;
  clumps.strength = 0.35;
  clumps.profile = 2;
  CurlDetail waves;
  waves.helical = false;
  waves.frequency = 1.6;
  waves.radius = 0.07;
  waves.radius_growth = 0.5;
  waves.phase_jitter = 0.12;
  FrizzDetail frizz;
  frizz.amplitude = 0.004;
  d.doc.execute(
      {"add details", SetDetails{{with_seed(clumps, 1), with_seed(waves, 2), with_seed(frizz, 3)}}, std::nullopt});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: lapis_make_sessions <source dir>\n");
    return 2;
  }
  const std::filesystem::path dir = std::filesystem::path(argv[1]) / "assets" / "sessions";
  const Head head = load_bundled_head(argv[1]);
  try {
    // §4.6's resolutions: about 25K unknowns for smooth styles, 50K for ponytails.
    // The gravity prior (gravity_prior.h) lets hair below the sketched curves fall instead of
    // spreading sideways over the shoulders. Not for the ponytails: their curves sweep the
    // front hair back from above, and where no curve reaches the hairline the prior would drop
    // it over the face.
    for (auto [name, unknowns, prior, draw] :
         {std::tuple{"smooth", 25000.0, 0.3, &smooth}, std::tuple{"parting", 25000.0, 0.3, &parting},
          std::tuple{"ponytails", 50000.0, 0.0, &ponytails}, std::tuple{"curly_bob", 25000.0, 0.3, &curly_bob},
          std::tuple{"wavy_long", 25000.0, 0.3, &wavy_long}, std::tuple{"half_up", 50000.0, 0.3, &half_up}}) {
      Drawer d = start(head, unknowns, prior);
      draw(d);
      save_session(dir / (std::string(name) + ".json"), d.doc.style());
      std::printf("%s: %zu primitives from %zu strokes\n", name, d.doc.style().primitives.size(),
                  d.doc.style().strokes.size());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lapis_make_sessions: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
