#include "lapis/geometry/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <streambuf>
#include <string>
#include <vector>

#include "lapis/core/error.h"

namespace lapis::geometry {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& what, int err) {
  throw IoError("geometry::write_file_atomically(): " + path.string() + ": " + what + ": " +
                std::strerror(err));
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

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  // Appending piecewise (not "." + name + ...) avoids a GCC 12 -Wrestrict false positive.
  std::string name(1, '.');
  name.append(path.filename().string()).append(".tmp.").append(std::to_string(::getpid()));
  name.append(".").append(std::to_string(counter++));
  return path.parent_path() / name;
}

void fsync_directory(const std::filesystem::path& dir) {
  const int fd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;  // durability of the rename is best effort; the file itself is synced
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  if (path.filename().empty()) fail(path, "not a file name", EINVAL);
  const std::filesystem::path tmp = temporary_sibling(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) fail(path, "cannot create temporary file " + tmp.string(), errno);
  auto abandon = [&] {
    ::close(fd);
    ::unlink(tmp.c_str());
  };
  int write_error = 0;
  try {
    FdBuf buf(fd);
    std::ostream out(&buf);
    write(out);
    out.flush();
    if (!out || buf.error()) write_error = buf.error() ? buf.error() : EIO;
  } catch (...) {
    abandon();
    throw;
  }
  if (write_error) {
    abandon();
    fail(path, "write failed", write_error);
  }
  if (::fsync(fd) != 0) {
    const int err = errno;
    abandon();
    fail(path, "fsync failed", err);
  }
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail(path, "close failed", err);
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    fail(path, "rename failed", err);
  }
  fsync_directory(path.parent_path());
}

}  // namespace lapis::geometry
