// Private helpers of the mesh readers: slurping a file with a size limit, a line/token cursor
// that tracks line numbers (CRLF and '#' comments accepted), strict number parsing, and the
// error format "<function>: <file>:<line>: <what was expected>".
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "lapis/core/error.h"

namespace lapis::geometry::detail {

// Reads the whole file; IoError "<fn>: <path>: cannot open: <reason>" on failure.
std::string read_file(const std::filesystem::path& path, std::string_view fn);

[[noreturn]] inline void io_fail(std::string_view fn, const std::filesystem::path& path, const std::string& where,
                                 const std::string& what) {
  throw IoError(std::string(fn) + ": " + path.string() + (where.empty() ? "" : ":" + where) + ": " + what);
}

// Quotes a token for an error message, cut to 20 characters and with non-printables escaped;
// an empty token reads "end of input".
std::string quote(std::string_view token);

// Parses the whole token as a finite double / an int; false on anything else.
inline bool parse_double(std::string_view s, double& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}
inline bool parse_int(std::string_view s, long long& out) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && p == s.data() + s.size();
}

// Walks a text buffer line by line and token by token.
class TextCursor {
 public:
  // first_line: the file's line number of text's first line (a PLY body after its header).
  TextCursor(std::string_view text, std::string_view fn, const std::filesystem::path& path, char comment = '#',
             int first_line = 1)
      : text_(text), fn_(fn), path_(path), comment_(comment), line_(first_line) {}

  // Next whitespace-separated token, crossing line ends and skipping comments;
  // empty at end of input.
  std::string_view token();
  // Next token on the current line only; empty at end of line.
  std::string_view token_on_line();
  // Skips the rest of the current line (including its end).
  void skip_line();
  // True when only blanks/comments remain before the end of the current line.
  bool at_line_end();
  bool at_end();
  // The remainder of the current line (without its end), and moves past it.
  std::string_view rest_of_line();

  int line() const { return line_; }
  size_t offset() const { return pos_; }
  size_t remaining() const { return text_.size() - pos_; }

  [[noreturn]] void fail(const std::string& what) const { io_fail(fn_, path_, "line " + std::to_string(line_), what); }
  // Token readers that fail with "expected <what>, found '<token>'".
  double number(std::string_view what);
  long long integer(std::string_view what, bool same_line = false);
  double number_on_line(std::string_view what);

 private:
  void skip_blanks();      // spaces, tabs, CR and comments (not LF)
  void skip_to_content();  // skip_blanks() across line ends
  std::string_view text_;
  std::string_view fn_;
  const std::filesystem::path& path_;
  char comment_;
  size_t pos_ = 0;
  int line_ = 1;
};

// Fails when the buffer holds a NUL byte: a text format got binary data.
void require_text(std::string_view text, std::string_view fn, const std::filesystem::path& path);

}  // namespace lapis::geometry::detail
