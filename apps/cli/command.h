// The `lapis` command line: one executable, a subcommand per module. Each subcommand lives
// in its own cmd_<name>.cpp and is listed once in commands.cpp.
#pragma once

#include <string>
#include <vector>

namespace lapis::cli {

struct Command {
  const char* name;
  const char* summary;  // one line for `lapis --help`
  const char* usage;    // the full `lapis <name> --help` text
  // Runs with the arguments after the subcommand's name; returns the exit status.
  // Throws lapis::Error (printed as one line, exit 1) or UsageError (exit 2).
  int (*run)(const std::vector<std::string>& args);
};

const std::vector<Command>& commands();

}  // namespace lapis::cli
