// Crash-safe file saving shared by every module: the content goes to a temporary file in the
// target's directory, is flushed to disk (fsync), then renamed over the target, so readers
// see either the old file or the complete new one, never a half-written file.
//
// The temporary file is `.<name>.lapis-tmp-<pid>-<n>` beside the target. One left behind by a
// killed process (kill -9 during a large export) is removed by the next write of the same
// target once no process of that pid exists. A target that is a symbolic link is written
// through it (the link stays a link); an existing target keeps its permission bits, a new one
// gets 0666 less the umask, as any other program's output would.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace lapis::core {

// Calls write(stream) on a binary stream into a temporary sibling of path, then fsyncs and
// renames it to path. If write throws or any I/O step fails, the temporary file is removed,
// path is left untouched, and the exception propagates (I/O failures as lapis::IoError
// "core::write_file_atomically(): <path>: <reason>"). Inside an AtomicFileGroup the
// rename waits for the group's commit().
void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write);

// Files that belong together (a .hair and its .obj, a mesh and its selection): while a group
// is alive on this thread, write_file_atomically writes and syncs each temporary file but does
// not rename it; commit() renames them all. A failure in any write, or a group destroyed
// without commit(), removes every temporary file, so all targets stay old. Only a rename
// itself failing part way (the directory vanishing) can leave some targets new.
class AtomicFileGroup {
 public:
  AtomicFileGroup();
  ~AtomicFileGroup();
  AtomicFileGroup(const AtomicFileGroup&) = delete;
  AtomicFileGroup& operator=(const AtomicFileGroup&) = delete;
  void commit();  // throws IoError naming the first rename that failed

  struct Staged {
    std::filesystem::path target, temporary;
  };

 private:
  std::vector<Staged> staged_;
  AtomicFileGroup* outer_;
  friend void write_file_atomically(const std::filesystem::path&, const std::function<void(std::ostream&)>&);
};

// Creates the directories above path that do not exist yet (outputs of the apps under out/).
// Throws IoError "core::create_parent_directories(): <path>: <reason>", e.g. when a
// component is a regular file, instead of std::filesystem::filesystem_error.
void create_parent_directories(const std::filesystem::path& path);

// The temporary files of `path` that write_file_atomically would remove as stale: those of
// processes that no longer exist. For tests and tools.
std::vector<std::filesystem::path> stale_temporaries(const std::filesystem::path& path);

}  // namespace lapis::core
