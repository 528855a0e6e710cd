// Private: when OpenMP loops are worth a thread team.
#pragma once

namespace lapis::geometry::detail {

// Loops over fewer items run serially: a team's start and barrier cost more than they save,
// and on a loaded machine a barrier can wait a whole scheduler slice for a descheduled
// thread (the test suite, which validates thousands of tiny meshes, ran 20x slower).
constexpr long kParallelMin = 20000;

}  // namespace lapis::geometry::detail
