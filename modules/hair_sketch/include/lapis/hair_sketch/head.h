// The head the hair grows on (thesis §4.3, §4.6): a closed mesh, its scalp region (from a
// mask file or a cap above a plane), a BVH for inside tests and closest points, and root
// sampling uniform in the spherical coordinates θ ∈ [0,180), φ ∈ [0,360) about the head
// centre with seeded jitter.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "lapis/geometry/bvh.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::hair_sketch {

struct Head {
  geometry::TriMesh mesh;
  std::vector<char> scalp_face;                      // #F, 1 for scalp faces
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // of the cranium: origin of θ, φ
  Eigen::AlignedBox3d box;
  std::shared_ptr<const geometry::Bvh> bvh;
  geometry::Vertices face_normals;  // #F unit outward normals
  // Steradians of the directions from `center` that leave the head through the scalp (set by
  // make_head(); sample_roots() derives its step from it).
  double scalp_solid_angle = 0;

  // Outward unit normal of the head at its point closest to p, and that point.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> closest(const Eigen::Vector3d& p) const;
  bool inside(const Eigen::Vector3d& p) const { return bvh->inside(p); }
  int scalp_face_count() const;
};

// Builds the head from a mesh: scalp faces = those whose three vertices are in
// scalp_vertices. The centre (origin of θ, φ) is the box centre in x and z and, in y, a
// quarter of the way up the scalp's height range: inside the cranium, not the neck.
// Throws InvalidArgument for an invalid mesh or out-of-range scalp indices.
Head make_head(geometry::TriMesh mesh, const std::vector<int>& scalp_vertices);

// Scalp vertices above the plane through `point` with normal `up` (the default scalp:
// the cap above a plane through the forehead and ears).
std::vector<int> scalp_vertices_above(const geometry::TriMesh& mesh, const Eigen::Vector3d& point,
                                      const Eigen::Vector3d& up);

// Reads a scalp mask: one vertex index per line, '#' comments. Throws IoError naming the
// file and line for anything else or an index outside [0, num_vertices).
std::vector<int> read_scalp_mask(const std::filesystem::path& path, int num_vertices);

// Loads a head mesh (OBJ/OFF/PLY) and its mask; without a mask the scalp is the cap above
// the plane 15% of the head box height above its centre (y up). Throws IoError for a
// malformed file, InvalidArgument for a mesh that is not a valid closed surface.
Head load_head(const std::filesystem::path& mesh_path, const std::filesystem::path& mask_path = {});

// The bundled head: assets/head.obj with assets/head_scalp.txt below source_dir.
Head load_bundled_head(const std::filesystem::path& source_dir);

struct RootOptions {
  // Density: number of roots wanted; the θ and φ sampling steps (thesis §4.6 "hair density
  // is controlled via the sampling steps of these two angles") are derived from it so that
  // roots are uniform per solid angle (φ step grows as 1/sin θ).
  // 5000 keeps the interactive loop's regrowth well within a frame; the thesis leaves the
  // density to the user (§4.6).
  int count = 5000;
  double jitter = 0.35;    // random offset in units of a step ("a small amount of randomness")
  std::uint32_t seed = 1;  // root jitter seed
  double lift = 1e-3;      // roots are moved this far (× head size) outward off the surface
};

// Root points on the scalp, never inside the head. Deterministic for a seed.
std::vector<Eigen::Vector3d> sample_roots(const Head& head, const RootOptions& options = {});

}  // namespace lapis::hair_sketch
