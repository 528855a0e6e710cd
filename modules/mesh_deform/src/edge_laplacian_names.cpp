#include <array>

#include "lapis/mesh_deform/edge_laplacian.h"

namespace lapis::mesh_deform {
namespace {

constexpr std::array kDomains{LaplacianDomain::Edges, LaplacianDomain::Vertices};
constexpr std::array kTransforms{CellTransform::Rotation, CellTransform::IsotropicScale,
                                 CellTransform::AnisotropicScale, CellTransform::Full};
constexpr std::array kFrames{ScaleFrame::World, ScaleFrame::RestPrincipal};

template <class E, std::size_t N>
E from_name(const std::array<E, N>& values, const std::string& name, const char* fn, const char* what) {
  std::string known;
  for (E v : values) {
    if (name == to_string(v)) return v;
    known += (known.empty() ? "" : ", ") + std::string(to_string(v));
  }
  throw InvalidArgument(std::string("mesh_deform::") + fn + "(): unknown " + what + " '" + name +
                        "', expected one of " + known);
}

}  // namespace

const char* to_string(LaplacianDomain d) { return d == LaplacianDomain::Edges ? "edges" : "vertices"; }

const char* to_string(CellTransform t) {
  switch (t) {
    case CellTransform::Rotation:
      return "rotation";
    case CellTransform::IsotropicScale:
      return "isotropic";
    case CellTransform::AnisotropicScale:
      return "anisotropic";
    case CellTransform::Full:
      return "full";
  }
  return "?";
}

const char* to_string(ScaleFrame f) { return f == ScaleFrame::World ? "world" : "principal"; }

LaplacianDomain laplacian_domain_from_name(const std::string& name) {
  return from_name(kDomains, name, "laplacian_domain_from_name", "domain");
}

CellTransform cell_transform_from_name(const std::string& name) {
  return from_name(kTransforms, name, "cell_transform_from_name", "transform");
}

ScaleFrame scale_frame_from_name(const std::string& name) {
  return from_name(kFrames, name, "scale_frame_from_name", "scale frame");
}

}  // namespace lapis::mesh_deform
