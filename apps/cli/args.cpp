#include "args.h"

#include "lapis/core/checked_number.h"

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

// The numbers are read by core's checked readers, like the numbers of every file format.
long Args::get_int(const std::string& flag, long fallback, long lo, long hi) const {
  const auto it = values_.find(flag);
  return it == values_.end() ? fallback : static_cast<long>(parse_integer<UsageError>(it->second, flag, lo, hi));
}

double Args::get_double(const std::string& flag, double fallback, double lo, double hi) const {
  const auto it = values_.find(flag);
  return it == values_.end() ? fallback : parse_finite<UsageError>(it->second, flag, lo, hi);
}

void Args::allow_only(const std::set<std::string>& known) const {
  for (const auto& f : present_)
    if (!known.count(f)) throw UsageError("unknown option " + f);
}

}  // namespace lapis::cli
