// A small `--flag value` parser for the `lapis` subcommands: typed getters whose errors name
// the flag, and a check that nothing unknown was given.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "lapis/core/error.h"

namespace lapis::cli {

// Thrown for a malformed command line; main() prints it with the usage and exits 2.
using UsageError = lapis::UsageError;

class Args {
 public:
  // `switches` are flags without a value (e.g. --scale-features).
  Args(const std::vector<std::string>& argv, const std::set<std::string>& switches = {});

  bool has(const std::string& flag) const;
  std::string get(const std::string& flag) const;  // required
  std::string get(const std::string& flag, const std::string& fallback) const;
  long get_int(const std::string& flag, long fallback, long lo, long hi) const;
  double get_double(const std::string& flag, double fallback, double lo, double hi) const;
  // Throws UsageError naming the first flag not in `known`.
  void allow_only(const std::set<std::string>& known) const;

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> present_;
};

}  // namespace lapis::cli
