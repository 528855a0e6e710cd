// Atomic file writes: a target's mode and symbolic links kept, temporaries of killed
// processes removed, and a group of writes renamed all together or not at all.
#include <doctest/doctest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lapis/core/atomic_file.h"
#include "lapis/core/error.h"

using namespace lapis::core;
namespace fs = std::filesystem;

namespace {
// A fresh directory per test binary run, removed at exit.
fs::path scratch_dir() {
  struct Scratch {
    fs::path dir = fs::temp_directory_path() / ("lapis_atomic_file_test_" + std::to_string(::getpid()));
    Scratch() {
      fs::remove_all(dir);
      fs::create_directories(dir);
    }
    ~Scratch() {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  };
  static const Scratch scratch;
  return scratch.dir;
}
}  // namespace

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
void write_text(const fs::path& p, const std::string& text) {
  write_file_atomically(p, [&](std::ostream& out) { out << text; });
}
size_t entries(const fs::path& dir) { return std::distance(fs::directory_iterator(dir), fs::directory_iterator()); }
}  // namespace

TEST_CASE("core: atomic writes keep a target's mode and write through symbolic links") {
  const fs::path dir = scratch_dir() / "links";
  fs::create_directories(dir / "real");
  write_text(dir / "real" / "private.txt", "old");
  fs::permissions(dir / "real" / "private.txt", fs::perms::owner_read | fs::perms::owner_write);
  write_text(dir / "real" / "private.txt", "new");
  CHECK(slurp(dir / "real" / "private.txt") == "new");
  CHECK(fs::status(dir / "real" / "private.txt").permissions() == (fs::perms::owner_read | fs::perms::owner_write));
  // A relative link, resolved from its own directory, and a link to a link.
  fs::create_symlink(fs::path("real") / "private.txt", dir / "link.txt");
  fs::create_symlink("link.txt", dir / "link2.txt");
  write_text(dir / "link2.txt", "through");
  CHECK(fs::is_symlink(fs::symlink_status(dir / "link.txt")));
  CHECK(fs::is_symlink(fs::symlink_status(dir / "link2.txt")));
  CHECK(slurp(dir / "real" / "private.txt") == "through");
  CHECK(fs::status(dir / "real" / "private.txt").permissions() == (fs::perms::owner_read | fs::perms::owner_write));
  CHECK(entries(dir / "real") == 1);
  CHECK(entries(dir) == 3);
}

TEST_CASE("core: an atomic write removes the temporary files that killed processes left") {
  const fs::path dir = scratch_dir() / "stale";
  fs::create_directories(dir);
  const fs::path target = dir / "strands.hair";
  // The pid of a process that has exited: a child that exits at once, reaped.
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  REQUIRE(child > 0);
  ::waitpid(child, nullptr, 0);
  const fs::path dead = dir / (".strands.hair.lapis-tmp-" + std::to_string(child) + "-0");
  const fs::path alive = dir / (".strands.hair.lapis-tmp-" + std::to_string(::getpid()) + "-999");
  const fs::path other = dir / (".other.hair.lapis-tmp-" + std::to_string(child) + "-0");
  for (const fs::path& p : {dead, alive, other}) std::ofstream(p) << "87 MB of a killed export";
  CHECK(stale_temporaries(target) == std::vector<fs::path>{dead});
  write_text(target, "complete");
  CHECK_FALSE(fs::exists(dead));
  CHECK(fs::exists(alive));  // a live process may still finish it
  CHECK(fs::exists(other));  // another target's
  CHECK(slurp(target) == "complete");
}

TEST_CASE("core: a group of atomic writes renames all files or none") {
  const fs::path dir = scratch_dir() / "group";
  fs::create_directories(dir);
  const fs::path a = dir / "s.hair", b = dir / "s.obj";
  write_text(a, "old a");
  write_text(b, "old b");
  CHECK_THROWS_AS(([&] {
                    AtomicFileGroup group;
                    write_text(a, "new a");
                    CHECK(slurp(a) == "old a");  // staged, not renamed
                    write_file_atomically(b, [](std::ostream& out) {
                      out << "half";
                      throw lapis::IoError("disk full");
                    });
                    group.commit();
                  }()),
                  lapis::IoError);
  CHECK(slurp(a) == "old a");
  CHECK(slurp(b) == "old b");
  CHECK(entries(dir) == 2);
  {
    AtomicFileGroup group;
    write_text(a, "abandoned");
  }  // no commit: nothing renamed
  CHECK(slurp(a) == "old a");
  CHECK(entries(dir) == 2);
  {
    AtomicFileGroup group;
    write_text(a, "new a");
    write_text(b, "new b");
    group.commit();
    write_text(dir / "after.txt", "direct");  // after commit, writes are renamed at once
    CHECK(fs::exists(dir / "after.txt"));
  }
  CHECK(slurp(a) == "new a");
  CHECK(slurp(b) == "new b");
  CHECK(entries(dir) == 3);
}
