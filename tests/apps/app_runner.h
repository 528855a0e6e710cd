// Runs the real apps in tests: under Xvfb (a private display per test run), headless or in
// a visible window driven by xdotool. Pixel checks read the screenshots back.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

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

// A private Xvfb server for the lifetime of the object. The server picks its own display
// number (-displayfd): it claims the first free one with an exclusive lock file and writes the
// number back only once it accepts connections, so concurrent servers (other test processes, a
// CI job's xvfb-run) cannot collide and nothing races its start-up. xvfb-run -a, used before,
// chose the number by looking for lock files and set up an xauth cookie; a CI run once found
// its display refusing the app ("Failed to open display :440"). This server has no cookie: it
// listens only on its local socket.
class XvfbServer {
 public:
  XvfbServer() {
    int fds[2];
    if (::pipe(fds) != 0) return;
    // Everything the child needs is prepared before fork: between fork and exec only
    // async-signal-safe calls.
    const std::string log = (scratch_dir() / "xvfb.log").string();
    const std::string fd = std::to_string(fds[1]);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(fds[0]);
      const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
      if (out >= 0) {
        ::dup2(out, STDOUT_FILENO);
        ::dup2(out, STDERR_FILENO);
      }
      ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1280x1024x24", "-nolisten", "tcp",
               static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(fds[1]);
    if (pid_ < 0) {
      ::close(fds[0]);
      return;
    }
    std::string number;
    pollfd p{fds[0], POLLIN, 0};
    char c = 0;
    // The number arrives as one line; a server that cannot start closes the pipe (read 0).
    while (::poll(&p, 1, 30000) == 1 && ::read(fds[0], &c, 1) == 1 && c != '\n') number += c;
    ::close(fds[0]);
    if (!number.empty() && number.find_first_not_of("0123456789") == std::string::npos) display_ = ":" + number;
  }
  ~XvfbServer() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  XvfbServer(const XvfbServer&) = delete;
  XvfbServer& operator=(const XvfbServer&) = delete;

  // ":N", or empty when the server did not start.
  const std::string& display() const { return display_; }

 private:
  pid_t pid_ = -1;
  std::string display_;
};

// `command` (a shell command line) with DISPLAY set to a fresh Xvfb server; -1 when no server
// started (the log is in scratch_dir()/xvfb.log).
inline int run_under_xvfb(const std::string& command) {
  const XvfbServer server;
  if (server.display().empty()) {
    std::fprintf(stderr, "run_under_xvfb: Xvfb did not start; see %s\n", (scratch_dir() / "xvfb.log").c_str());
    return -1;
  }
  return run("DISPLAY=" + server.display() + "; export DISPLAY; unset XAUTHORITY; " + command);
}

// Shell functions for scripts that drive an app in a window (xdotool). The app runs with
// --ready-file "$READY" and rewrites it as "frame=F events=N buttons=B keys=K busy=0|1" after
// its first frame and after every frame that handled input: scripts wait for the state they
// need instead of sleeping a fixed time that a loaded machine outlasts.
//   wait_ready CONDITION [SECONDS]  until CONDITION (sh, over $frame $events $buttons $keys
//                                   $busy) holds; status 4 after SECONDS (default 300)
//   mark                            remembers the counts handled so far ($mark_events, ...)
//   wait_handled KEYS BUTTONS       until KEYS key and BUTTONS mouse button events more than at
//                                   the mark were handled and the app is idle (xdotool key
//                                   ctrl+s is 4 key events, a click 2 button events)
//   window NAME                     sets $w to the app's window once its first frame is drawn
//   quit_discarding                 Ctrl+Q to $w; when the app asks about unsaved work
//                                   (asking=1), D discards it; waits for $app to exit
inline const char* kReadyFunctions = R"SH(
wait_ready() {
  i=0
  while [ $i -lt $(( ${2:-300} * 20 )) ]; do
    if [ -s "$READY" ]; then eval "$(cat "$READY")"; if eval "$1"; then return 0; fi; fi
    sleep 0.05; i=$((i + 1))
  done
  echo "wait_ready: '$1' never held; last state: $(cat "$READY" 2>/dev/null)" >&2
  return 4
}
mark() { wait_ready true; mark_events=$events; mark_keys=$keys; mark_buttons=$buttons; }
wait_handled() {
  wait_ready "[ \$keys -ge $((mark_keys + $1)) ] && [ \$buttons -ge $((mark_buttons + $2)) ] && [ \$busy -eq 0 ]"
}
quit_discarding() {
  xdotool key --window $w ctrl+q
  while kill -0 $app 2>/dev/null; do
    eval "$(cat "$READY")"
    [ "${asking:-0}" = 1 ] && xdotool key --window $w d
    sleep 0.1
  done
  wait $app
}
window() {
  wait_ready true || return 3
  w=$(xdotool search --name "$1" 2>/dev/null | head -n1)
  [ -n "$w" ] || return 3
}
)SH";

// Writes a sh script of the ready functions, READY=ready_file and body to path; returns the
// command that runs it.
inline std::string ready_script(const fs::path& path, const fs::path& ready_file, const std::string& body) {
  fs::remove(ready_file);
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return "false";
  std::fprintf(f, "READY='%s'\n%s\n%s\n", ready_file.c_str(), kReadyFunctions, body.c_str());
  std::fclose(f);
  return "sh " + path.string();
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
