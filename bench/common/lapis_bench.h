// Shared helpers of the benchmarks: wall-clock timing, medians, a printed table and the
// JSON file in bench/results/. Benchmarks measure ratios against a baseline in the same
// run, because machines here are shared and noisy.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "allocator_name.h"

namespace lapis::bench {

inline double now_ms() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double, std::milli>(clock::now().time_since_epoch()).count();
}

// Runs f() and returns its wall time in milliseconds.
template <class F>
double time_ms(F&& f) {
  const double t0 = now_ms();
  f();
  return now_ms() - t0;
}

inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

// A plain fixed-width table printed to stdout.
class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }
  void print() const {
    std::vector<size_t> w(header_.size(), 0);
    auto widen = [&](const std::vector<std::string>& r) {
      for (size_t i = 0; i < r.size() && i < w.size(); ++i) w[i] = std::max(w[i], r[i].size());
    };
    widen(header_);
    for (const auto& r : rows_) widen(r);
    auto line = [&](const std::vector<std::string>& r) {
      for (size_t i = 0; i < w.size(); ++i)
        std::printf("%*s  ", static_cast<int>(w[i]), i < r.size() ? r[i].c_str() : "");
      std::printf("\n");
    };
    line(header_);
    for (const auto& r : rows_) line(r);
    std::fflush(stdout);
  }

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

inline std::string fmt(double v, int digits = 1) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// Writes bench/results/<name>.json (atomically: temporary file, then rename).
// The figures depend on the allocator (cmake/LapisAllocator.cmake), so the file names it.
inline std::filesystem::path write_results(const std::string& name, nlohmann::json j) {
  if (j.is_object() && !j.contains("allocator")) j["allocator"] = allocator_name();
  const std::filesystem::path dir = std::filesystem::path(LAPIS_SOURCE_DIR) / "bench" / "results";
  std::filesystem::create_directories(dir);
  const auto path = dir / (name + ".json");
  const auto tmp = dir / (name + ".json.tmp");
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
  }
  std::filesystem::rename(tmp, path);
  std::printf("wrote %s (allocator: %s)\n", path.string().c_str(), allocator_name().c_str());
  return path;
}

// Peak resident set size of this process in MiB (Linux /proc).
inline double peak_rss_mib() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kb = 0;
      status >> kb;
      return kb / 1024.0;
    }
  }
  return 0.0;
}

// For a benchmark's main(): --help or -h prints `usage` and exits 0; an option (an argument
// starting with "--") not among `options` prints which and the usage and exits 2. Asking what a
// benchmark does then never starts it, and a typo does not start a long run on the defaults.
inline void check_options(int argc, char** argv, std::initializer_list<std::string_view> options, const char* usage) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--help" || a == "-h") {
      std::printf("%s", usage);
      std::exit(0);
    }
    if (a.starts_with("--") && std::find(options.begin(), options.end(), a) == options.end()) {
      std::fprintf(stderr, "unknown option %s\n%s", argv[i], usage);
      std::exit(2);
    }
  }
}

// Runs `cmd` (a child benchmark process printing one line of JSON) and returns its output;
// empty with a message on stderr when it fails. Each row in its own process keeps its peak
// memory its own.
inline std::string run_child(const std::string& cmd, const char* who) {
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (p && std::fgets(buf, sizeof buf, p)) out += buf;
  const int status = p ? pclose(p) : -1;
  if (status != 0 || out.empty()) {
    std::fprintf(stderr, "%s: '%s' failed (status %d)\n", who, cmd.c_str(), status);
    return {};
  }
  return out;
}

}  // namespace lapis::bench
