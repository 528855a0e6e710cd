#include "command.h"

namespace lapis::cli {

// One declaration and one table row per subcommand (each defined in its cmd_<name>.cpp).
extern const Command kMeshCommand;
extern const Command kHairCommand;
extern const Command kMergeCommand;
extern const Command kDeformCommand;
extern const Command kFeaturesCommand;

const std::vector<Command>& commands() {
  static const std::vector<Command> all = {
      kMeshCommand, kHairCommand, kMergeCommand, kDeformCommand, kFeaturesCommand,
  };
  return all;
}

}  // namespace lapis::cli
