// Runs the real apps in tests: under Xvfb (a private display per test run), headless or in
// a visible window driven by xdotool. Pixel checks read the screenshots back.
#pragma once

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <thread>

#include "lapis/viewer/png.h"

namespace lapis::apps_test {

namespace fs = std::filesystem;

inline fs::path scratch_dir() {
  const fs::path d = fs::temp_directory_path() / ("lapis_apps_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

// Runs a shell command; returns its exit status.
inline int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// `command` under a fresh Xvfb server. xvfb-run -a takes the first display number without a
// lock file from its start number, so two test processes (or a test and another xvfb-run on
// the machine) starting together can pick the same one and one app finds no display: start
// each process's search at its own number.
inline int run_under_xvfb(const std::string& command) {
  const int first_display = 100 + static_cast<int>(getpid() % 400) * 2;
  return run("xvfb-run -a -n " + std::to_string(first_display) + " -s '-screen 0 1280x1024x24' " + command);
}

// Fraction of pixels that differ from the image's top-left (background) pixel.
inline double foreground_fraction(const viewer::Image& img) {
  size_t differ = 0;
  const std::uint8_t* bg = img.rgba.data();
  for (size_t k = 0; k < img.rgba.size(); k += 4) {
    const int d = std::abs(img.rgba[k] - bg[0]) + std::abs(img.rgba[k + 1] - bg[1]) + std::abs(img.rgba[k + 2] - bg[2]);
    if (d > 24) ++differ;
  }
  return static_cast<double>(differ) / static_cast<double>(img.rgba.size() / 4);
}

}  // namespace lapis::apps_test
