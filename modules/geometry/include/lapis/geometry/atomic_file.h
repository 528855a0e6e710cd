// Crash-safe file saving shared by every module: the content goes to a temporary file in the
// target's directory, is flushed to disk (fsync), then renamed over the target, so readers
// see either the old file or the complete new one, never a half-written file.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace lapis::geometry {

// Calls write(stream) on a binary stream into a temporary sibling of path, then fsyncs and
// renames it to path. If write throws or any I/O step fails, the temporary file is removed,
// path is left untouched, and the exception propagates (I/O failures as lapis::IoError
// "geometry::write_file_atomically(): <path>: <reason>").
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace lapis::geometry
