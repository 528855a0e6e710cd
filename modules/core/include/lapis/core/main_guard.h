// The error handling of every Lapis program's main(): one line on stderr naming the program,
// and an exit status a script can tell apart.
#pragma once

#include <functional>
#include <string>

namespace lapis::core {

// Runs body and returns its status. A UsageError prints "PROGRAM: MESSAGE" and then `usage`
// (or "(see --help)" when usage is empty) and returns 2; any other lapis::Error prints
// "PROGRAM: error: MESSAGE" and returns 1; any other exception (out of memory, a bug) prints
// "PROGRAM: internal error: MESSAGE" and returns 1, instead of aborting.
int guarded_main(const std::string& program, const std::function<int()>& body, const std::string& usage = {});

}  // namespace lapis::core
