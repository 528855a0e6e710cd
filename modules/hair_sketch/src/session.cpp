// JSON sessions: writer, validating reader, head resolution.
#include "lapis/hair_sketch/session.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "lapis/core/atomic_file.h"
#include "lapis/core/checked_number.h"
#include "lapis/core/error.h"

namespace lapis::hair_sketch {
using hair_field::FieldMethod;

namespace {

using nlohmann::json;

// ---- writing ----

json to_json(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json to_json(const std::vector<Eigen::Vector3d>& p) {
  json a = json::array();
  for (const auto& v : p) a.push_back(to_json(v));
  return a;
}

json to_json(const Stroke& s) {
  json a = json::array();
  for (const auto& q : s) a.push_back(json::array({q.x(), q.y()}));
  return a;
}

json to_json(const geometry::CameraMatrices& c) {
  json view = json::array(), proj = json::array();
  for (int r = 0; r < 4; ++r)
    for (int k = 0; k < 4; ++k) view.push_back(c.view(r, k)), proj.push_back(c.projection(r, k));
  return {{"view", view},
          {"projection", proj},
          {"viewport", json::array({c.viewport[0], c.viewport[1], c.viewport[2], c.viewport[3]})}};
}

json to_json(const StrandDetail& d) {
  json j = {{"type", detail_type(d)}, {"seed", d.seed}, {"region", d.region}};
  if (const auto* c = std::get_if<CurlDetail>(&d.shape)) {
    j.update({{"frequency", c->frequency},
              {"radius", c->radius},
              {"frequency_growth", c->frequency_growth},
              {"radius_growth", c->radius_growth},
              {"phase_jitter", c->phase_jitter},
              {"radius_jitter", c->radius_jitter},
              {"root_fade", c->root_fade}});
  } else if (const auto* k = std::get_if<ClumpDetail>(&d.shape)) {
    j.update({{"clumps", k->clumps}, {"strength", k->strength}, {"profile", k->profile}});
  } else if (const auto* f = std::get_if<FrizzDetail>(&d.shape)) {
    j.update({{"amplitude", f->amplitude}, {"wavelength", f->wavelength}, {"root_fade", f->root_fade}});
  } else if (const auto* l = std::get_if<LengthDetail>(&d.shape)) {
    j["variation"] = l->variation;
  } else {
    const auto& cut = std::get<CutDetail>(d.shape);
    j["camera"] = to_json(cut.camera);
    j["line"] = to_json(cut.line);
  }
  return j;
}

json to_json(const StylePrimitive& p) {
  json j = {{"type", primitive_type(p)}, {"viewpoint", to_json(p.viewpoint)}, {"support", to_string(p.support)}};
  if (p.mirrored) j["mirrored"] = true;  // optional: false when absent
  if (const auto* s = std::get_if<StreamCurve>(&p.shape)) {
    j["points"] = to_json(s->points);
    j["tail_segments"] = s->tail_segments;
  } else if (const auto* d = std::get_if<DividingCurve>(&p.shape)) {
    j["points"] = to_json(d->points);
    j["alpha0"] = d->alpha0;
    j["alpha1"] = d->alpha1;
    j["sigma"] = d->sigma;
    j["height"] = d->height;
    j["discontinuity"] = d->discontinuity;
    j["samples_per_side"] = d->samples_per_side;
  } else {
    const auto& t = std::get<Ponytail>(p.shape);
    j["spine"] = to_json(t.spine);
    j["cross_section"] = to_json(t.cross_section);
    j["profile_a"] = to_json(t.profile_a);
    j["profile_b"] = to_json(t.profile_b);
    j["tightness"] = t.tightness;
    j["inner_ratio"] = t.inner_ratio;
    j["outer_ratio"] = t.outer_ratio;
  }
  return j;
}

const char* method_name(FieldMethod m) {
  switch (m) {
    case FieldMethod::Auto:
      return "auto";
    case FieldMethod::Thesis:
      return "thesis";
    case FieldMethod::Refactorize:
      return "refactorize";
    case FieldMethod::Multigrid:
      return "multigrid";
  }
  return "?";
}

// ---- reading ----

class Reader {
 public:
  Reader(std::string source, const SessionLimits& limits) : source_(std::move(source)), lim_(limits) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw IoError(where(path) + ": " + what);
  }
  std::string where(const std::string& path) const {
    return "hair_sketch::session_from_json(): " + source_ + ": " + path;
  }
  static const char* type_name(const json& j) { return j.type_name(); }

  const json& key(const json& obj, const std::string& path, const char* k) const {
    if (!obj.is_object()) fail(path, std::string("expected an object, got ") + type_name(obj));
    const auto it = obj.find(k);
    if (it == obj.end()) fail(path, std::string("missing key \"") + k + "\"");
    return *it;
  }
  double number(const json& j, const std::string& path, double lo = -kAnyFinite, double hi = kAnyFinite) const {
    if (!j.is_number()) fail(path, std::string("expected a number, got ") + type_name(j));
    return json_finite<IoError>(j, where(path), lo, hi);
  }
  double number(const json& obj, const std::string& path, const char* k, double lo, double hi) const {
    return number(key(obj, path, k), path + "." + k, lo, hi);
  }
  long long integer(const json& obj, const std::string& path, const char* k, long long lo, long long hi) const {
    const json& j = key(obj, path, k);
    if (!j.is_number_integer()) fail(path + "." + k, std::string("expected an integer, got ") + type_name(j));
    return json_integer<IoError>(j, where(path + "." + k), lo, hi);
  }
  bool boolean(const json& obj, const std::string& path, const char* k) const {
    const json& j = key(obj, path, k);
    if (!j.is_boolean()) fail(path + "." + k, std::string("expected a boolean, got ") + type_name(j));
    return j.get<bool>();
  }
  std::string string(const json& obj, const std::string& path, const char* k) const {
    const json& j = key(obj, path, k);
    if (!j.is_string()) fail(path + "." + k, std::string("expected a string, got ") + type_name(j));
    return j.get<std::string>();
  }
  const json& array(const json& j, const std::string& path, std::size_t max, std::size_t exact = 0) const {
    if (!j.is_array()) fail(path, std::string("expected an array, got ") + type_name(j));
    if (exact && j.size() != exact)
      fail(path, "expected " + std::to_string(exact) + " elements, got " + std::to_string(j.size()));
    if (j.size() > max) fail(path, std::to_string(j.size()) + " elements, at most " + std::to_string(max) + " allowed");
    return j;
  }
  template <int N>
  Eigen::Matrix<double, N, 1> vec(const json& j, const std::string& path) const {
    array(j, path, N, N);
    Eigen::Matrix<double, N, 1> v;
    for (int i = 0; i < N; ++i) v[i] = number(j[i], path + "[" + std::to_string(i) + "]");
    return v;
  }
  std::vector<Eigen::Vector3d> points(const json& obj, const std::string& path, const char* k) const {
    const std::string p = path + "." + k;
    const json& a = array(key(obj, path, k), p, lim_.max_points);
    std::vector<Eigen::Vector3d> out;
    out.reserve(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) out.push_back(vec<3>(a[i], p + "[" + std::to_string(i) + "]"));
    return out;
  }
  Stroke stroke(const json& j, const std::string& path) const {
    const json& a = array(j, path, lim_.max_points);
    Stroke out;
    out.reserve(a.size());
    for (std::size_t i = 0; i < a.size(); ++i) out.push_back(vec<2>(a[i], path + "[" + std::to_string(i) + "]"));
    return out;
  }
  geometry::CameraMatrices camera(const json& obj, const std::string& path) const {
    geometry::CameraMatrices c;
    const auto mat = [&](const char* k, Eigen::Matrix4d& m) {
      const std::string p = path + "." + k;
      const json& a = array(key(obj, path, k), p, 16, 16);
      for (int i = 0; i < 16; ++i) m(i / 4, i % 4) = number(a[i], p + "[" + std::to_string(i) + "]");
    };
    mat("view", c.view);
    mat("projection", c.projection);
    c.viewport = vec<4>(key(obj, path, "viewport"), path + ".viewport");
    if (!(c.viewport[2] > 0 && c.viewport[3] > 0)) fail(path + ".viewport", "expected a positive width and height");
    return c;
  }
  SupportMode support(const json& obj, const std::string& path) const {
    const std::string s = string(obj, path, "support");
    if (s == "ruled") return SupportMode::Ruled;
    if (s == "strip") return SupportMode::Strip;
    fail(path + ".support", "expected \"ruled\" or \"strip\", got \"" + s + "\"");
  }
  FieldMethod method(const json& obj, const std::string& path) const {
    const std::string s = string(obj, path, "field_method");
    for (FieldMethod m : {FieldMethod::Auto, FieldMethod::Thesis, FieldMethod::Refactorize, FieldMethod::Multigrid})
      if (s == method_name(m)) return m;
    fail(path + ".field_method", "expected auto, thesis, refactorize or multigrid, got \"" + s + "\"");
  }
  StylePrimitive primitive(const json& j, const std::string& path) const {
    StylePrimitive p;
    p.viewpoint = vec<3>(key(j, path, "viewpoint"), path + ".viewpoint");
    p.support = support(j, path);
    if (j.contains("mirrored")) p.mirrored = boolean(j, path, "mirrored");
    const std::string type = string(j, path, "type");
    if (type == "stream_curve") {
      StreamCurve s;
      s.points = points(j, path, "points");
      s.tail_segments = static_cast<int>(integer(j, path, "tail_segments", 0, 1000));
      p.shape = std::move(s);
    } else if (type == "dividing_curve") {
      DividingCurve d;
      d.points = points(j, path, "points");
      d.alpha0 = number(j, path, "alpha0", -10, 10);
      d.alpha1 = number(j, path, "alpha1", -10, 10);
      d.sigma = number(j, path, "sigma", 1e-6, 1e3);
      d.height = number(j, path, "height", -1e3, 1e3);
      d.discontinuity = number(j, path, "discontinuity", 0, 10);
      d.samples_per_side = static_cast<int>(integer(j, path, "samples_per_side", 0, 1000));
      p.shape = std::move(d);
    } else if (type == "ponytail") {
      Ponytail t;
      t.spine = points(j, path, "spine");
      t.cross_section = points(j, path, "cross_section");
      t.profile_a = points(j, path, "profile_a");
      t.profile_b = points(j, path, "profile_b");
      t.tightness = number(j, path, "tightness", 0, 10);
      t.inner_ratio = number(j, path, "inner_ratio", 0, 100);
      t.outer_ratio = number(j, path, "outer_ratio", 0, 100);
      p.shape = std::move(t);
    } else {
      fail(path + ".type", "expected stream_curve, dividing_curve or ponytail, got \"" + type + "\"");
    }
    return p;
  }
  StrandDetail detail(const json& j, const std::string& path) const {
    StrandDetail d;
    d.seed = static_cast<std::uint32_t>(integer(j, path, "seed", 0, 0xffffffffLL));
    const json& region = array(key(j, path, "region"), path + ".region", 100'000'000);
    for (std::size_t i = 0; i < region.size(); ++i) {
      const std::string at = path + ".region[" + std::to_string(i) + "]";
      if (!region[i].is_number_integer()) fail(at, std::string("expected an integer, got ") + type_name(region[i]));
      d.region.push_back(static_cast<int>(json_integer<IoError>(region[i], where(at), 0, (1LL << 31) - 1)));
    }
    const std::string type = string(j, path, "type");
    if (type == "curl" || type == "wave") {
      CurlDetail c;
      c.helical = type == "curl";
      c.frequency = number(j, path, "frequency", 1e-9, 1e6);
      c.radius = number(j, path, "radius", 0, 1e6);
      c.frequency_growth = number(j, path, "frequency_growth", -0.99, 1e6);
      c.radius_growth = number(j, path, "radius_growth", -1, 1e6);
      c.phase_jitter = number(j, path, "phase_jitter", 0, 1);
      c.radius_jitter = number(j, path, "radius_jitter", 0, 1);
      c.root_fade = number(j, path, "root_fade", 0, 1e6);
      d.shape = c;
    } else if (type == "clump") {
      ClumpDetail c;
      c.clumps = static_cast<int>(integer(j, path, "clumps", 1, 10'000'000));
      c.strength = number(j, path, "strength", 0, 1);
      c.profile = number(j, path, "profile", 1e-3, 1e3);
      d.shape = c;
    } else if (type == "frizz") {
      FrizzDetail f;
      f.amplitude = number(j, path, "amplitude", 0, 1e6);
      f.wavelength = number(j, path, "wavelength", 1e-9, 1e6);
      f.root_fade = number(j, path, "root_fade", 0, 1e6);
      d.shape = f;
    } else if (type == "length") {
      d.shape = LengthDetail{number(j, path, "variation", 0, 1)};
    } else if (type == "cut") {
      CutDetail c;
      c.camera = camera(key(j, path, "camera"), path + ".camera");
      c.line = stroke(key(j, path, "line"), path + ".line");
      if (c.line.size() < 2) fail(path + ".line", "a cut line needs at least two points");
      d.shape = c;
    } else {
      fail(path + ".type", "expected curl, wave, clump, frizz, length or cut, got \"" + type + "\"");
    }
    return d;
  }
  RecordedStroke recorded(const json& j, const std::string& path) const {
    RecordedStroke r;
    const std::string action = string(j, path, "action");
    bool known = false;
    for (StrokeAction a : {StrokeAction::StreamCurve, StrokeAction::DividingCurve, StrokeAction::Hint,
                           StrokeAction::Tilt, StrokeAction::Ponytail})
      if (action == to_string(a)) r.action = a, known = true;
    if (!known) fail(path + ".action", "unknown action \"" + action + "\"");
    if (j.contains("target")) r.target = static_cast<int>(integer(j, path, "target", -1, 1 << 30));
    r.camera = camera(key(j, path, "camera"), path + ".camera");
    if (j.contains("mirrored")) r.mirrored = boolean(j, path, "mirrored");
    if (j.contains("cameras")) {
      const json& cams = array(j["cameras"], path + ".cameras", 4);
      for (std::size_t i = 0; i < cams.size(); ++i)
        r.cameras.push_back(camera(cams[i], path + ".cameras[" + std::to_string(i) + "]"));
    }
    const json& a = array(key(j, path, "strokes"), path + ".strokes", 4);
    for (std::size_t i = 0; i < a.size(); ++i)
      r.strokes.push_back(stroke(a[i], path + ".strokes[" + std::to_string(i) + "]"));
    return r;
  }
  HairstyleSettings settings(const json& j, const std::string& path) const {
    HairstyleSettings s;
    s.head_mesh = string(j, path, "head_mesh");
    s.scalp_mask = string(j, path, "scalp_mask");
    s.grid.target_unknowns = number(j, path, "grid_unknowns", 8, 1e9);
    s.field_method = method(j, path);
    s.field.omega = number(j, path, "omega", 1e-6, 1e12);
    s.roots.count = static_cast<int>(integer(j, path, "roots", 0, 10'000'000));
    s.roots.seed = static_cast<std::uint32_t>(integer(j, path, "seed", 0, 0xffffffffLL));
    s.growth.step = number(j, path, "step", 1e-3, 10);
    s.growth.max_length = number(j, path, "max_length", 0, 1e6);
    if (j.contains("keep_outside_head"))  // optional: on when absent
      s.growth.keep_outside_head = boolean(j, path, "keep_outside_head");
    if (j.contains("head_clearance")) s.growth.head_clearance = number(j, path, "head_clearance", 0, 1);
    s.scalp_avoidance = boolean(j, path, "scalp_avoidance");
    s.support = support(j, path);
    s.sketch.tail_segments = static_cast<int>(integer(j, path, "tail_segments", 0, 1000));
    if (j.contains("gravity_prior"))  // optional: off when absent
      s.gravity_prior.strength = number(j, path, "gravity_prior", 0, 10);
    if (j.contains("field_detail_amplitude")) {  // optional: off when absent
      s.field_detail.amplitude = number(j, path, "field_detail_amplitude", 0, 1e6);
      s.field_detail.wavelength = number(j, path, "field_detail_wavelength", 1e-9, 1e6);
    }
    return s;
  }

 private:
  std::string source_;
  const SessionLimits& lim_;
};

}  // namespace

std::string session_to_json(const Hairstyle& style) {
  const HairstyleSettings& s = style.settings;
  json j;
  j["format"] = "lapis-hair-session";
  j["version"] = 1;
  j["settings"] = {{"head_mesh", s.head_mesh},
                   {"scalp_mask", s.scalp_mask},
                   {"grid_unknowns", s.grid.target_unknowns},
                   {"field_method", method_name(s.field_method)},
                   {"omega", s.field.omega},
                   {"roots", s.roots.count},
                   {"seed", s.roots.seed},
                   {"step", s.growth.step},
                   {"max_length", s.growth.max_length},
                   {"scalp_avoidance", s.scalp_avoidance},
                   {"support", to_string(s.support)},
                   {"tail_segments", s.sketch.tail_segments}};
  // Written where they differ from the defaults, so that sessions without them read the same.
  if (!s.growth.keep_outside_head) j["settings"]["keep_outside_head"] = false;
  if (s.growth.head_clearance != GrowthOptions{}.head_clearance)
    j["settings"]["head_clearance"] = s.growth.head_clearance;
  if (s.gravity_prior.strength > 0) j["settings"]["gravity_prior"] = s.gravity_prior.strength;
  if (s.field_detail.amplitude > 0) {
    j["settings"]["field_detail_amplitude"] = s.field_detail.amplitude;
    j["settings"]["field_detail_wavelength"] = s.field_detail.wavelength;
  }
  j["camera"] = to_json(style.camera);
  j["primitives"] = json::array();
  for (const auto& p : style.primitives) j["primitives"].push_back(to_json(p));
  if (!style.details.empty()) {  // optional: sessions without detail read as before
    j["details"] = json::array();
    for (const auto& d : style.details) j["details"].push_back(to_json(d));
  }
  j["strokes"] = json::array();
  for (const auto& r : style.strokes) {
    json strokes = json::array();
    for (const auto& st : r.strokes) strokes.push_back(to_json(st));
    j["strokes"].push_back(
        {{"action", to_string(r.action)}, {"target", r.target}, {"camera", to_json(r.camera)}, {"strokes", strokes}});
    if (r.mirrored) j["strokes"].back()["mirrored"] = true;
    if (!r.cameras.empty()) {
      json cameras = json::array();
      for (const auto& c : r.cameras) cameras.push_back(to_json(c));
      j["strokes"].back()["cameras"] = cameras;
    }
  }
  return j.dump(1);
}

Hairstyle session_from_json(std::string_view text, const std::string& source, const SessionLimits& limits) {
  const Reader rd(source, limits);
  json j;
  try {
    j = json::parse(text.begin(), text.end());
  } catch (const json::exception& e) {  // syntax errors, and numbers beyond double (1e999)
    rd.fail("$", std::string("malformed JSON: ") + e.what());
  }
  if (rd.string(j, "$", "format") != "lapis-hair-session") rd.fail("$.format", "expected \"lapis-hair-session\"");
  if (rd.integer(j, "$", "version", 1, 1000) != 1) rd.fail("$.version", "unsupported version, expected 1");
  Hairstyle h;
  h.settings = rd.settings(rd.key(j, "$", "settings"), "$.settings");
  h.camera = rd.camera(rd.key(j, "$", "camera"), "$.camera");
  const json& prims = rd.array(rd.key(j, "$", "primitives"), "$.primitives", limits.max_items);
  for (std::size_t i = 0; i < prims.size(); ++i)
    h.primitives.push_back(rd.primitive(prims[i], "$.primitives[" + std::to_string(i) + "]"));
  if (j.contains("details")) {
    const json& details = rd.array(j["details"], "$.details", limits.max_items);
    for (std::size_t i = 0; i < details.size(); ++i)
      h.details.push_back(rd.detail(details[i], "$.details[" + std::to_string(i) + "]"));
  }
  if (j.contains("strokes")) {
    const json& st = rd.array(j["strokes"], "$.strokes", limits.max_items);
    for (std::size_t i = 0; i < st.size(); ++i)
      h.strokes.push_back(rd.recorded(st[i], "$.strokes[" + std::to_string(i) + "]"));
  }
  return h;
}

namespace {

// An absolute path as a session at `path` stores it: relative to the session's directory, so a
// session and its head move together and no machine's absolute paths are written.
std::string stored_path(const std::filesystem::path& path, const std::string& p) {
  if (p.empty() || !std::filesystem::path(p).is_absolute()) return p;
  const auto dir = std::filesystem::absolute(path).parent_path().lexically_normal();
  const auto rel = std::filesystem::path(p).lexically_normal().lexically_relative(dir);
  return rel.empty() ? p : rel.generic_string();
}

}  // namespace

void save_session(const std::filesystem::path& path, const Hairstyle& style) {
  Hairstyle stored = style;
  stored.settings.head_mesh = stored_path(path, style.settings.head_mesh);
  stored.settings.scalp_mask = stored_path(path, style.settings.scalp_mask);
  const std::string text = session_to_json(stored);
  core::write_file_atomically(path, [&](std::ostream& out) { out << text << '\n'; });
}

Hairstyle load_session(const std::filesystem::path& path, const SessionLimits& limits) {
  const std::string where = "hair_sketch::load_session(): " + path.string() + ": ";
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(where + "cannot read: " + ec.message());
  if (size > limits.max_file_bytes)
    throw IoError(where + std::to_string(size) + " bytes, at most " + std::to_string(limits.max_file_bytes) +
                  " allowed");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(where + "cannot open");
  std::ostringstream buf;
  buf << in.rdbuf();
  return session_from_json(buf.str(), path.string(), limits);
}

Head load_session_head(const Hairstyle& style, const std::filesystem::path& session_path,
                       const std::filesystem::path& mesh_override) {
  const std::filesystem::path dir = session_path.parent_path();
  const auto resolve = [&](const std::string& p) -> std::filesystem::path {
    if (p.empty()) return {};
    const std::filesystem::path q(p);
    return q.is_absolute() ? q : dir / q;
  };
  if (!mesh_override.empty()) return load_head(mesh_override);
  if (style.settings.head_mesh.empty())
    throw IoError("hair_sketch::load_session_head(): " + session_path.string() +
                  ": settings.head_mesh is empty and no head mesh was given");
  return load_head(resolve(style.settings.head_mesh), resolve(style.settings.scalp_mask));
}

}  // namespace lapis::hair_sketch
