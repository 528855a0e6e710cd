// The one exception hierarchy of Lapis. Every module throws a subclass of lapis::Error;
// messages start with the throwing function's name and say what was expected
// (Magnum style: "solver::Cholesky::solve(): right-hand side has 7 rows, expected 9").
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace lapis {

// Base of every error Lapis throws. Catch this to catch them all.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An argument is out of its domain: wrong sizes, indices out of range, NaN, empty input.
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

// A command line is malformed: an unknown flag, a missing value, a value out of its range.
// Programs report it with their usage and exit with status 2 (see main_guard.h).
class UsageError : public InvalidArgument {
 public:
  using InvalidArgument::InvalidArgument;
};

// A file could not be read or written, or its content is malformed. The message names the
// file and the line or byte offset.
class IoError : public Error {
 public:
  using Error::Error;
};

// A matrix that must be symmetric positive definite is not. `column()` is the column
// (in the caller's ordering where known, else the factor's) where the factorization broke.
class NotPositiveDefinite : public Error {
 public:
  NotPositiveDefinite(const std::string& what, std::ptrdiff_t column) : Error(what), column_(column) {}
  std::ptrdiff_t column() const { return column_; }

 private:
  std::ptrdiff_t column_;
};

// The sparse solver backend failed for another reason (out of memory, internal error);
// the message carries the backend's own status text.
class SolverFailure : public Error {
 public:
  using Error::Error;
};

// A request would need more memory than the caller allowed (e.g. a grid too fine).
class ResourceLimit : public Error {
 public:
  using Error::Error;
};

}  // namespace lapis
