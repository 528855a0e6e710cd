#include "io_text.h"

#include <cerrno>
#include <cstring>
#include <fstream>

namespace lapis::geometry::detail {

std::string read_file(const std::filesystem::path& path, std::string_view fn) {
  std::ifstream in(path, std::ios::binary);
  if (!in) io_fail(fn, path, "", std::string("cannot open: ") + std::strerror(errno));
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) io_fail(fn, path, "", "is a directory, expected a file");
  std::string data;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size > 0) {
    data.resize(static_cast<size_t>(size));
    in.seekg(0);
    in.read(data.data(), size);
    if (in.gcount() != size) io_fail(fn, path, "", "read failed after " + std::to_string(in.gcount()) + " bytes");
  }
  return data;
}

std::string quote(std::string_view token) {
  if (token.empty()) return "end of input";
  std::string out = "'";
  for (size_t i = 0; i < token.size() && i < 20; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  if (token.size() > 20) out += "...";
  return out + "'";
}

void require_text(std::string_view text, std::string_view fn, const std::filesystem::path& path) {
  const size_t nul = text.find('\0');
  if (nul != std::string_view::npos)
    io_fail(fn, path, "byte " + std::to_string(nul), "binary data (NUL byte), expected text");
}

void TextCursor::skip_blanks() {
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
      ++pos_;
    } else if (c == comment_) {
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else {
      break;
    }
  }
}

std::string_view TextCursor::token_on_line() {
  skip_blanks();
  const size_t begin = pos_;
  while (pos_ < text_.size()) {
    const char c = text_[pos_];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v' || c == comment_) break;
    ++pos_;
  }
  return text_.substr(begin, pos_ - begin);
}

void TextCursor::skip_to_content() {
  for (;;) {
    skip_blanks();
    if (pos_ >= text_.size() || text_[pos_] != '\n') return;
    ++pos_;
    ++line_;
  }
}

std::string_view TextCursor::token() {
  skip_to_content();
  return token_on_line();
}

void TextCursor::skip_line() {
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  if (pos_ < text_.size()) {
    ++pos_;
    ++line_;
  }
}

bool TextCursor::at_line_end() {
  skip_blanks();
  return pos_ >= text_.size() || text_[pos_] == '\n';
}

bool TextCursor::at_end() {
  skip_to_content();
  return pos_ >= text_.size();
}

std::string_view TextCursor::rest_of_line() {
  const size_t begin = pos_;
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
  std::string_view line = text_.substr(begin, pos_ - begin);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  if (pos_ < text_.size()) {
    ++pos_;
    ++line_;
  }
  return line;
}

namespace {
double checked_number(const TextCursor& c, std::string_view t, std::string_view what) {
  double v = 0;
  if (t.empty()) c.fail("expected " + std::string(what) + ", found end of " + (c.remaining() ? "line" : "file"));
  if (!parse_double(t, v)) c.fail("expected " + std::string(what) + ", found " + quote(t));
  if (!std::isfinite(v)) c.fail("non-finite " + std::string(what) + " " + quote(t));
  return v;
}
}  // namespace

double TextCursor::number(std::string_view what) { return checked_number(*this, token(), what); }

double TextCursor::number_on_line(std::string_view what) { return checked_number(*this, token_on_line(), what); }

long long TextCursor::integer(std::string_view what, bool same_line) {
  const std::string_view t = same_line ? token_on_line() : token();
  long long v = 0;
  if (t.empty()) fail("expected " + std::string(what) + ", found end of " + (remaining() ? "line" : "file"));
  if (!parse_int(t, v)) fail("expected " + std::string(what) + ", found " + quote(t));
  return v;
}

}  // namespace lapis::geometry::detail
