// PLY (Turk's Stanford format): a text header of elements and their scalar or list
// properties, then the body in ASCII or binary little/big endian. Any scalar type may hold
// coordinates, any list count/item types the faces; other elements are read and dropped.
// Reference: Paul Bourke's "PLY - Polygon File Format" page.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "io_text.h"
#include "lapis/core/format.h"
#include "lapis/geometry/io.h"
#include "mesh_builder.h"

namespace lapis::geometry {
namespace {

constexpr const char* kRead = "geometry::read_ply()";

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool parse_type(std::string_view s, Type& t) {
  static const std::pair<std::string_view, Type> names[] = {
      {"char", Type::Int8},     {"int8", Type::Int8},       {"uchar", Type::UInt8},    {"uint8", Type::UInt8},
      {"short", Type::Int16},   {"int16", Type::Int16},     {"ushort", Type::UInt16},  {"uint16", Type::UInt16},
      {"int", Type::Int32},     {"int32", Type::Int32},     {"uint", Type::UInt32},    {"uint32", Type::UInt32},
      {"float", Type::Float32}, {"float32", Type::Float32}, {"double", Type::Float64}, {"float64", Type::Float64}};
  for (const auto& [name, type] : names)
    if (s == name) return t = type, true;
  return false;
}

size_t type_size(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::UInt8:
      return 1;
    case Type::Int16:
    case Type::UInt16:
      return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32:
      return 4;
    case Type::Float64:
      return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  Type type = Type::Float32;  // the item type for lists
  bool is_list = false;
  Type count_type = Type::UInt8;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

enum class Encoding { Ascii, Little, Big };

struct Header {
  Encoding encoding = Encoding::Ascii;
  std::vector<Element> elements;
  size_t body_offset = 0;
};

Header parse_header(const std::string& text, const std::filesystem::path& path) {
  if (text.empty()) detail::io_fail(kRead, path, "line 1", "empty file, expected 'ply' magic");
  size_t end = text.find("end_header");
  if (text.compare(0, 3, "ply") != 0 || (text.size() > 3 && text[3] != '\n' && text[3] != '\r'))
    detail::io_fail(kRead, path, "line 1", "expected 'ply' magic, found " + detail::quote(text.substr(0, 8)));
  if (end == std::string::npos)
    detail::io_fail(kRead, path, "", "no 'end_header' line, expected a complete PLY header");
  Header h;
  const std::string_view header(text.data(), end);
  detail::TextCursor in(header, kRead, path, '\0');
  in.rest_of_line();  // "ply"
  bool have_format = false;
  while (!in.at_end()) {
    const std::string_view keyword = in.token_on_line();
    if (keyword == "comment" || keyword == "obj_info") {
      in.rest_of_line();
      continue;
    }
    if (keyword == "format") {
      const std::string_view f = in.token_on_line();
      if (f == "ascii")
        h.encoding = Encoding::Ascii;
      else if (f == "binary_little_endian")
        h.encoding = Encoding::Little;
      else if (f == "binary_big_endian")
        h.encoding = Encoding::Big;
      else
        in.fail("unknown format " + detail::quote(f) + ", expected ascii, binary_little_endian or binary_big_endian");
      if (in.token_on_line() != "1.0") in.fail("expected format version 1.0");
      have_format = true;
    } else if (keyword == "element") {
      Element e;
      e.name = std::string(in.token_on_line());
      if (e.name.empty()) in.fail("expected an element name");
      e.count = in.integer("element count", true);
      if (e.count < 0) in.fail("negative count " + std::to_string(e.count) + " for element '" + e.name + "'");
      h.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (h.elements.empty()) in.fail("property before any element");
      Property p;
      std::string_view t = in.token_on_line();
      if (t == "list") {
        p.is_list = true;
        const std::string_view ct = in.token_on_line();
        if (!parse_type(ct, p.count_type)) in.fail("unknown list count type " + detail::quote(ct));
        if (p.count_type == Type::Float32 || p.count_type == Type::Float64)
          in.fail("list count type " + detail::quote(ct) + " is not an integer type");
        t = in.token_on_line();
      }
      if (!parse_type(t, p.type))
        in.fail("unknown property type " + detail::quote(t) +
                ", expected char, uchar, short, ushort, int, uint, float, double or their sized names");
      p.name = std::string(in.token_on_line());
      if (p.name.empty()) in.fail("expected a property name");
      h.elements.back().properties.push_back(std::move(p));
    } else {
      in.fail("unknown header keyword " + detail::quote(keyword) + ", expected format, element, property or comment");
    }
    if (!in.at_line_end()) in.fail("unexpected text after '" + std::string(keyword) + "' statement");
  }
  if (!have_format) detail::io_fail(kRead, path, "", "no 'format' line in the header");
  end = text.find('\n', end);
  h.body_offset = end == std::string::npos ? text.size() : end + 1;
  return h;
}

// Reads scalars from the body, ASCII tokens or binary bytes, and names the position on error.
class Body {
 public:
  Body(const std::string& text, const Header& h, const std::filesystem::path& path)
      : text_(text),
        path_(path),
        encoding_(h.encoding),
        pos_(h.body_offset),
        ascii_(std::string_view(text).substr(h.body_offset), kRead, path, '\0',
               1 + static_cast<int>(
                       std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(h.body_offset), '\n'))) {}

  size_t remaining() const { return encoding_ == Encoding::Ascii ? ascii_.remaining() : text_.size() - pos_; }
  bool ascii() const { return encoding_ == Encoding::Ascii; }

  [[noreturn]] void fail(const std::string& what) const {
    if (ascii()) ascii_.fail(what);
    detail::io_fail(kRead, path_, "byte " + std::to_string(pos_), what);
  }

  // what/e/i name the value in error messages only (built on failure: this is the hot loop).
  double scalar(Type t, std::string_view what, const Element& e, long long i) {
    auto where = [&] { return std::string(what) + " of " + e.name + " " + std::to_string(i); };
    if (ascii()) {
      const std::string_view tok = ascii_.token();
      double v = 0;
      if (tok.empty()) fail("file ends early, expected " + where());
      if (!detail::parse_double(tok, v)) fail("expected " + where() + ", found " + detail::quote(tok));
      return v;
    }
    const size_t n = type_size(t);
    if (text_.size() - pos_ < n) fail("file ends early, expected " + where() + " (" + std::to_string(n) + " bytes)");
    unsigned char b[8];
    std::memcpy(b, text_.data() + pos_, n);
    pos_ += n;
    if ((encoding_ == Encoding::Little) != (std::endian::native == std::endian::little))
      for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    return decode(t, b);
  }

  bool at_end() { return ascii() ? ascii_.at_end() : pos_ == text_.size(); }

 private:
  static double decode(Type t, const unsigned char* b) {
    switch (t) {
      case Type::Int8:
        return static_cast<double>(static_cast<std::int8_t>(b[0]));
      case Type::UInt8:
        return b[0];
      case Type::Int16: {
        std::int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Type::UInt16: {
        std::uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case Type::Int32: {
        std::int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Type::UInt32: {
        std::uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Type::Float32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case Type::Float64: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
    }
    return 0;
  }

  const std::string& text_;
  const std::filesystem::path& path_;
  Encoding encoding_;
  size_t pos_;
  detail::TextCursor ascii_;
};

bool is_face_indices(const Element& e, const Property& p) {
  return e.name == "face" && p.is_list && (p.name == "vertex_indices" || p.name == "vertex_index");
}

// Fewest bytes one instance of e can take: claimed counts above remaining / this are lies.
// A face's index list holds at least 3 items, so a face costs at least 1 + 3 bytes, and
// the 12 bytes a triangle takes in memory stay within a small multiple of the file size.
size_t min_instance_bytes(const Element& e, bool ascii) {
  size_t n = 0;
  for (const Property& p : e.properties) {
    const size_t item = ascii ? 2 : type_size(p.type);
    n += ascii ? 2 : type_size(p.is_list ? p.count_type : p.type);
    if (is_face_indices(e, p)) n += 3 * item;
  }
  return std::max<size_t>(n, 1);
}

long long list_count(Body& body, const Property& p, const Element& e, long long i) {
  auto where = [&] { return e.name + " " + std::to_string(i); };
  const double c = body.scalar(p.count_type, "list count", e, i);
  if (!(c >= 0) || c != std::floor(c)) body.fail("invalid list count " + std::to_string(c) + " of " + where());
  // Compared as doubles: an ASCII count of 1e37 is whole but no integer type holds it.
  const size_t item = body.ascii() ? 2 : type_size(p.type);
  if (c > static_cast<double>(body.remaining() / item))
    body.fail("list count " + format_number(c) + " of " + where() + " exceeds the remaining " +
              std::to_string(body.remaining()) + " bytes");
  return static_cast<long long>(c);
}

}  // namespace

TriMesh read_ply(const std::filesystem::path& path, Warnings* warnings) {
  const std::string text = detail::read_file(path, kRead);
  const Header h = parse_header(text, path);
  Body body(text, h, path);

  const Element* vertex = nullptr;
  long long nv = 0, nf = 0;
  unsigned long long needed = 0;
  for (const Element& e : h.elements) {
    if (e.name == "vertex") vertex = &e, nv = e.count;
    if (e.name == "face") nf = e.count;
    const size_t per = min_instance_bytes(e, body.ascii());
    if (static_cast<unsigned long long>(e.count) > body.remaining() / per ||
        (needed += static_cast<unsigned long long>(e.count) * per) > body.remaining())
      body.fail("element '" + e.name + "' claims " + std::to_string(e.count) + " instances, more than the remaining " +
                std::to_string(body.remaining()) + " bytes can hold");
  }
  if (!vertex) detail::io_fail(kRead, path, "", "no 'vertex' element in the header");
  int xyz[3] = {-1, -1, -1};
  for (size_t i = 0; i < vertex->properties.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (vertex->properties[i].name == std::string(1, static_cast<char>('x' + k)) && !vertex->properties[i].is_list)
        xyz[k] = static_cast<int>(i);
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
    detail::io_fail(kRead, path, "", "element 'vertex' lacks scalar properties x, y and z");

  detail::MeshBuilder mesh;
  mesh.reserve(static_cast<size_t>(nv), static_cast<size_t>(nf));
  std::vector<int> corners;
  bool have_faces = false;
  for (const Element& e : h.elements) {
    const bool is_vertex = &e == vertex;
    const Property* indices = nullptr;
    for (const Property& p : e.properties)
      if (is_face_indices(e, p)) indices = &p;
    if (e.name == "face" && !indices)
      detail::io_fail(kRead, path, "", "element 'face' has no list property 'vertex_indices'");
    if (!is_vertex && !indices && warnings && e.count > 0)
      warnings->push_back(std::string(kRead) + ": " + path.string() + ": ignored element '" + e.name + "'");
    have_faces = have_faces || indices;
    for (long long i = 0; i < e.count; ++i) {
      double p[3] = {0, 0, 0};
      auto where = [&] { return e.name + " " + std::to_string(i); };
      for (size_t j = 0; j < e.properties.size(); ++j) {
        const Property& prop = e.properties[j];
        if (prop.is_list) {
          const long long n = list_count(body, prop, e, i);
          if (&prop == indices) {
            if (n < 3) body.fail(where() + " has " + std::to_string(n) + " corners, expected at least 3");
            corners.resize(static_cast<size_t>(n));
          }
          for (long long k = 0; k < n; ++k) {
            const double v = body.scalar(prop.type, "list item", e, i);
            if (&prop != indices) continue;
            if (!(v >= 0 && v < static_cast<double>(nv)) || v != static_cast<double>(static_cast<long long>(v)))
              body.fail(where() + " index " + std::to_string(v) + " out of range [0, " + std::to_string(nv) + ")");
            corners[static_cast<size_t>(k)] = static_cast<int>(v);
          }
          if (&prop == indices) mesh.add_polygon(corners);
        } else {
          const double v = body.scalar(prop.type, prop.name, e, i);
          for (int k = 0; k < 3; ++k)
            if (is_vertex && static_cast<int>(j) == xyz[k]) {
              if (!std::isfinite(v)) body.fail("non-finite coordinate " + prop.name + " of " + where());
              p[k] = v;
            }
        }
      }
      if (is_vertex) mesh.add_vertex(p[0], p[1], p[2]);
    }
  }
  if (!body.at_end()) body.fail("unexpected data after the last element, counts in the header disagree with the data");
  if (!have_faces && warnings)
    warnings->push_back(std::string(kRead) + ": " + path.string() + ": no faces (point cloud)");
  return mesh.finish(kRead, path, warnings);
}

namespace {
template <class T>
void put(std::string& s, T v, bool swap) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}
}  // namespace

void write_ply(const std::filesystem::path& path, const TriMesh& mesh, PlyFormat format) {
  require_indices_in_range(mesh, "geometry::write_ply()");
  require_finite_vertices(mesh, "geometry::write_ply()");
  const char* name = format == PlyFormat::Ascii                ? "ascii"
                     : format == PlyFormat::BinaryLittleEndian ? "binary_little_endian"
                                                               : "binary_big_endian";
  const bool swap = format != PlyFormat::Ascii &&
                    ((format == PlyFormat::BinaryLittleEndian) != (std::endian::native == std::endian::little));
  core::write_file_atomically(path, [&](std::ostream& out) {
    std::string s = std::string("ply\nformat ") + name + " 1.0\ncomment written by Lapis\nelement vertex " +
                    std::to_string(mesh.num_vertices()) +
                    "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                    std::to_string(mesh.num_faces()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      for (int k = 0; k < 3; ++k) {
        if (format == PlyFormat::Ascii) {
          if (k) s += ' ';
          detail::append_number(s, mesh.V(v, k));
        } else {
          put(s, mesh.V(v, k), swap);
        }
      }
      if (format == PlyFormat::Ascii) s += '\n';
      if (s.size() > (1 << 16)) out << s, s.clear();
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
      if (format == PlyFormat::Ascii) {
        s += "3";
        for (int k = 0; k < 3; ++k) s += ' ', detail::append_number(s, static_cast<long long>(mesh.F(f, k)));
        s += '\n';
      } else {
        s += static_cast<char>(3);
        for (int k = 0; k < 3; ++k) put(s, static_cast<std::int32_t>(mesh.F(f, k)), swap);
      }
      if (s.size() > (1 << 16)) out << s, s.clear();
    }
    out << s;
  });
}

}  // namespace lapis::geometry
