#include "command.h"

namespace lapis::cli {

// One declaration and one table row per subcommand (each defined in its cmd_<name>.cpp).
extern const Command kMeshCommand;
extern const Command kHairCommand;
extern const Command kMergeCommand;
extern const Command kDeformCommand;
extern const Command kFeaturesCommand;
extern const Command kTransferCommand;

const std::vector<Command>& commands() {
  static const std::vector<Command> all = {
      kMeshCommand, kHairCommand, kMergeCommand, kDeformCommand, kFeaturesCommand, kTransferCommand,
  };
  return all;
}

}  // namespace lapis::cli
