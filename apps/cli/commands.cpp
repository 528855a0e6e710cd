#include "command.h"

namespace lapis::cli {

// One declaration and one table row per subcommand (each defined in its cmd_<name>.cpp).
extern const Command kMeshCommand;
extern const Command kMergeCommand;

const std::vector<Command>& commands() {
  static const std::vector<Command> all = {
      kMeshCommand,
      kMergeCommand,
  };
  return all;
}

}  // namespace lapis::cli
