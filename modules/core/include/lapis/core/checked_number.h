// Numbers read from text and JSON, checked where they are read: integral, in range before
// they are narrowed, finite. A vertex index of 4294967301 must not become vertex 5, 1.5 must
// not become 1, and 1e20 must not become INT_MIN. One family of readers shared by every file
// format and the command line, so all of them refuse the same values with the same words.
// Errors name the field (`what`) and the value found; the exception type is the caller's
// (IoError for file content, InvalidArgument by default).
#pragma once

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "lapis/core/error.h"
#include "lapis/core/format.h"

namespace lapis {

namespace detail {
// A token or JSON value quoted for a message, cut to 40 characters.
inline std::string quoted(std::string_view s) {
  std::string q(1, '\'');
  q.append(s.substr(0, 40)).append(s.size() > 40 ? "...'" : "'");
  return q;
}
template <class E>
[[noreturn]] void number_error(const std::string& what, const std::string& expected, const std::string& found) {
  throw E(what + ": expected " + expected + ", found " + found);
}
inline std::string integer_range(long long lo, long long hi) {
  return "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
}
inline std::string number_range(double lo, double hi) {
  if (lo == -std::numeric_limits<double>::max() && hi == std::numeric_limits<double>::max()) return "a finite number";
  return "a finite number in [" + format_number(lo) + ", " + format_number(hi) + "]";
}
}  // namespace detail

constexpr double kAnyFinite = std::numeric_limits<double>::max();
constexpr long long kAnyIndex = INT_MAX + 1LL;  // a size that admits every non-negative int

// All of `text` as a decimal integer (optional sign) in [lo, hi].
template <class E = InvalidArgument>
long long parse_integer(std::string_view text, const std::string& what, long long lo, long long hi) {
  std::string_view s = text;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  long long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec == std::errc::invalid_argument || end != s.data() + s.size())
    detail::number_error<E>(what, detail::integer_range(lo, hi), detail::quoted(text));
  if (ec == std::errc::result_out_of_range || v < lo || v > hi)
    detail::number_error<E>(what, detail::integer_range(lo, hi), std::string(text));
  return v;
}

// An index into something of `size` elements, in [0, min(size, kAnyIndex)), from text.
template <class E = InvalidArgument>
int parse_index(std::string_view text, const std::string& what, long long size = kAnyIndex) {
  return static_cast<int>(parse_integer<E>(text, what, 0, std::min(size, kAnyIndex) - 1));
}

// All of `text` as a finite number in [lo, hi].
template <class E = InvalidArgument>
double parse_finite(std::string_view text, const std::string& what, double lo = -kAnyFinite, double hi = kAnyFinite) {
  std::string_view s = text;
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec == std::errc::invalid_argument || end != s.data() + s.size())
    detail::number_error<E>(what, detail::number_range(lo, hi), detail::quoted(text));
  if (ec == std::errc::result_out_of_range || !std::isfinite(v) || v < lo || v > hi)
    detail::number_error<E>(what, detail::number_range(lo, hi), std::string(text.substr(0, 40)));
  return v;
}

// A value already in memory, e.g. computed from read numbers, or an output about to be written.
template <class E = InvalidArgument>
double check_finite(double v, const std::string& what, double lo = -kAnyFinite, double hi = kAnyFinite) {
  if (!(std::isfinite(v) && v >= lo && v <= hi))
    detail::number_error<E>(what, detail::number_range(lo, hi), format_number(v));
  return v;
}

// JSON values, for any nlohmann::basic_json (core does not depend on the library). An integer
// must be a JSON integer: 5.0 and 1.5 are refused alike, as are integers beyond long long.
template <class E = InvalidArgument, class Json>
long long json_integer(const Json& j, const std::string& what, long long lo, long long hi) {
  if (j.is_number_unsigned() && j.template get<unsigned long long>() > static_cast<unsigned long long>(LLONG_MAX))
    detail::number_error<E>(what, detail::integer_range(lo, hi), j.dump());
  if (!j.is_number_integer()) detail::number_error<E>(what, detail::integer_range(lo, hi), detail::quoted(j.dump()));
  const long long v = j.template get<long long>();
  if (v < lo || v > hi) detail::number_error<E>(what, detail::integer_range(lo, hi), std::to_string(v));
  return v;
}

template <class E = InvalidArgument, class Json>
int json_index(const Json& j, const std::string& what, long long size = kAnyIndex) {
  return static_cast<int>(json_integer<E>(j, what, 0, std::min(size, kAnyIndex) - 1));
}

template <class E = InvalidArgument, class Json>
double json_finite(const Json& j, const std::string& what, double lo = -kAnyFinite, double hi = kAnyFinite) {
  if (!j.is_number()) detail::number_error<E>(what, detail::number_range(lo, hi), detail::quoted(j.dump()));
  return check_finite<E>(j.template get<double>(), what, lo, hi);
}

}  // namespace lapis
