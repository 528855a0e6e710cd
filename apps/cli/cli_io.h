// What every `lapis` subcommand reads and writes the same way: input meshes pass the checks
// that `lapis mesh` reports, and a report is refused, not written with nulls, when a number in
// it is not finite (nlohmann writes NaN and infinity as null).
#pragma once

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "args.h"
#include "lapis/core/atomic_file.h"
#include "lapis/core/error.h"
#include "lapis/core/format.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::cli {

// read_mesh, then geometry::validate's checks (those of `lapis mesh`): "<path>: invalid mesh: ...".
inline geometry::TriMesh read_valid_mesh(const std::string& path) {
  geometry::TriMesh mesh = geometry::read_mesh(path);
  geometry::require_valid(mesh, {}, path);
  return mesh;
}

// Throws lapis::Error naming the first number of `j` that is not finite, e.g. "report.seam.dihedral_max_deg".
inline void require_finite_numbers(const nlohmann::json& j, const std::string& where) {
  if (j.is_number_float() && !std::isfinite(j.get<double>()))
    throw Error(where + " is " + format_number(j.get<double>()) + ", expected a finite number");
  if (j.is_object())
    for (const auto& [k, v] : j.items()) require_finite_numbers(v, where + "." + k);
  if (j.is_array())
    for (size_t i = 0; i < j.size(); ++i) require_finite_numbers(j[i], where + "[" + std::to_string(i) + "]");
}

// Prints the report and writes it to --report when given, after checking that it is finite.
inline void emit_report(const nlohmann::json& j, const Args& args) {
  require_finite_numbers(j, "report");
  const std::string text = j.dump(2);
  std::printf("%s\n", text.c_str());
  if (args.has("--report"))
    core::write_file_atomically(args.get("--report"), [&](std::ostream& out) { out << text << "\n"; });
}

}  // namespace lapis::cli
