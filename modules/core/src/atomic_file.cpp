#include "lapis/core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <streambuf>
#include <string>
#include <vector>

#include "lapis/core/error.h"

namespace lapis::core {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, int err) {
  throw IoError("core::write_file_atomically(): " + path.string() + ": " + what + ": " + std::strerror(err));
}

// A stream buffer straight onto a POSIX descriptor, so that we can fsync what we wrote
// (std::ofstream gives no access to its descriptor).
class FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd), buffer_(1 << 16) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!flush_buffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return flush_buffer() ? 0 : -1; }

 private:
  bool flush_buffer() {
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<size_t>(pptr() - p));
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      p += n;
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return true;
  }
  int fd_;
  int error_ = 0;
  std::vector<char> buffer_;
};

constexpr const char* kTmpTag = ".lapis-tmp-";

// ".<name>.lapis-tmp-": the prefix of every temporary file of a target called <name>.
std::string temporary_prefix(const std::filesystem::path& target) {
  // Appending piecewise (not "." + name + ...) avoids a GCC 12 -Wrestrict false positive.
  std::string name(1, '.');
  name.append(target.filename().string()).append(kTmpTag);
  return name;
}

std::filesystem::path temporary_sibling(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  std::string name = temporary_prefix(target);
  name.append(std::to_string(::getpid())).append("-").append(std::to_string(counter++));
  return target.parent_path() / name;
}

// The file a write of `path` replaces: symbolic links followed (relative ones from their own
// directory), so that renaming over it keeps the links.
std::filesystem::path resolve_links(const std::filesystem::path& path) {
  std::filesystem::path p = path;
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(p, ec))) return p;
    const std::filesystem::path link = std::filesystem::read_symlink(p, ec);
    if (ec) fail(path, "cannot read symbolic link " + p.string(), ec.value());
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  fail(path, "cannot resolve symbolic links", ELOOP);
}

void fsync_directory(const std::filesystem::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;  // durability of the rename is best effort; the file itself is synced
  ::fsync(fd);
  ::close(fd);
}

// Writes, syncs and closes the temporary file of `target`; removes it on any failure.
void write_temporary(const std::filesystem::path& path, const AtomicFileGroup::Staged& f,
                     const std::function<void(std::ostream&)>& write) {
  const int fd = ::open(f.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) fail(path, "cannot create temporary file " + f.temporary.string(), errno);
  auto abandon = [&](const std::string& what, int err) {
    ::close(fd);
    ::unlink(f.temporary.c_str());
    fail(path, what, err);
  };
  struct stat st {};
  if (::stat(f.target.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::fchmod(fd, st.st_mode & 07777) != 0)
    abandon("cannot keep the permissions of " + f.target.string(), errno);
  int write_error = 0;
  try {
    FdBuf buf(fd);
    std::ostream out(&buf);
    write(out);
    out.flush();
    if (!out || buf.error()) write_error = buf.error() ? buf.error() : EIO;
  } catch (...) {
    ::close(fd);
    ::unlink(f.temporary.c_str());
    throw;
  }
  if (write_error) abandon("write failed", write_error);
  if (::fsync(fd) != 0) abandon("fsync failed", errno);
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(f.temporary.c_str());
    fail(path, "close failed", err);
  }
}

void rename_into_place(const AtomicFileGroup::Staged& f, const std::filesystem::path& path) {
  if (::rename(f.temporary.c_str(), f.target.c_str()) != 0) {
    const int err = errno;
    ::unlink(f.temporary.c_str());
    fail(path, "rename failed", err);
  }
  fsync_directory(f.target.parent_path());
}

thread_local AtomicFileGroup* current_group = nullptr;

}  // namespace

void create_parent_directories(const std::filesystem::path& path) {
  if (!path.has_parent_path()) return;
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  if (ec)
    throw IoError("core::create_parent_directories(): " + path.string() + ": cannot create directory " +
                  path.parent_path().string() + ": " + ec.message());
}

std::vector<std::filesystem::path> stale_temporaries(const std::filesystem::path& path) {
  const std::filesystem::path target = resolve_links(path);
  const std::string prefix = temporary_prefix(target);
  std::vector<std::filesystem::path> out;
  std::error_code ec;
  const std::filesystem::path dir = target.parent_path().empty() ? "." : target.parent_path();
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    // "<pid>-<n>": a process that no longer exists cannot finish it.
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH)
      out.push_back(target.parent_path() / name);
  }
  return out;
}

void write_file_atomically(const std::filesystem::path& path, const std::function<void(std::ostream&)>& write) {
  if (path.filename().empty()) fail(path, "not a file name", EINVAL);
  const std::filesystem::path target = resolve_links(path);
  for (const auto& stale : stale_temporaries(target)) ::unlink(stale.c_str());
  const AtomicFileGroup::Staged f{target, temporary_sibling(target)};
  write_temporary(path, f, write);
  if (current_group) return current_group->staged_.push_back(f);
  rename_into_place(f, path);
}

AtomicFileGroup::AtomicFileGroup() : outer_(current_group) { current_group = this; }

AtomicFileGroup::~AtomicFileGroup() {
  for (const Staged& f : staged_) ::unlink(f.temporary.c_str());
  if (current_group == this) current_group = outer_;
}

void AtomicFileGroup::commit() {
  current_group = outer_;
  std::vector<Staged> files = std::move(staged_);
  staged_.clear();
  if (outer_) {  // nested: the outer group renames them with its own
    for (Staged& f : files) outer_->staged_.push_back(std::move(f));
    return;
  }
  for (size_t k = 0; k < files.size(); ++k) {
    try {
      rename_into_place(files[k], files[k].target);
    } catch (...) {
      for (size_t j = k + 1; j < files.size(); ++j) ::unlink(files[j].temporary.c_str());
      throw;
    }
  }
}

}  // namespace lapis::core
