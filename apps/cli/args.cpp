#include "args.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "lapis/core/format.h"

namespace lapis::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& switches) {
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.rfind("--", 0) != 0) throw UsageError("unexpected argument '" + a + "'");
    if (present_.count(a)) throw UsageError(a + " given twice");
    present_.insert(a);
    if (switches.count(a)) continue;
    if (i + 1 >= argv.size()) throw UsageError(a + " needs a value");
    values_[a] = argv[++i];
  }
}

bool Args::has(const std::string& flag) const { return present_.count(flag) > 0; }

std::string Args::get(const std::string& flag) const {
  const auto it = values_.find(flag);
  if (it == values_.end()) throw UsageError(flag + " is required");
  return it->second;
}

std::string Args::get(const std::string& flag, const std::string& fallback) const {
  const auto it = values_.find(flag);
  return it == values_.end() ? fallback : it->second;
}

long Args::get_int(const std::string& flag, long fallback, long lo, long hi) const {
  const auto it = values_.find(flag);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(it->second.c_str(), &end, 10);
  if (errno || end == it->second.c_str() || *end)
    throw UsageError(flag + " expects an integer, got '" + it->second + "'");
  if (v < lo || v > hi)
    throw UsageError(flag + " must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + it->second);
  return v;
}

double Args::get_double(const std::string& flag, double fallback, double lo, double hi) const {
  const auto it = values_.find(flag);
  if (it == values_.end()) return fallback;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (end == it->second.c_str() || *end || !std::isfinite(v))
    throw UsageError(flag + " expects a finite number, got '" + it->second + "'");
  if (v < lo || v > hi)
    throw UsageError(flag + " must be in [" + format_number(lo) + ", " + format_number(hi) + "], got " + it->second);
  return v;
}

void Args::allow_only(const std::set<std::string>& known) const {
  for (const auto& f : present_)
    if (!known.count(f)) throw UsageError("unknown option " + f);
}

}  // namespace lapis::cli
