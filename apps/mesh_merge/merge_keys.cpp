// The merge app's keyboard shortcuts (docs/apps.md lists them): tools, modes, merge, the
// optimal mode's region and the fixed features, undo and export.
#include <GLFW/glfw3.h>

#include "merge_app.h"

namespace lapis::merge_app {

bool MergeApp::handle_key(viewer::Viewer& v, const viewer::InputEvent& e) {
  if (e.action != GLFW_PRESS) return false;
  const bool ctrl = e.mods & GLFW_MOD_CONTROL, shift = e.mods & GLFW_MOD_SHIFT;
  if (ctrl && e.key == GLFW_KEY_Z) return shift ? redo(v) : undo(v), true;
  if (ctrl && e.key == GLFW_KEY_Y) return redo(v), true;
  if (ctrl && e.key == GLFW_KEY_E) return export_pending_ = true, true;
  if (ctrl) return false;
  switch (e.key) {
    case GLFW_KEY_1:
      tool_ = Tool::PairLoops;
      break;
    case GLFW_KEY_2:
      tool_ = Tool::Keys;
      break;
    case GLFW_KEY_3:
      tool_ = Tool::Handles;
      break;
    case GLFW_KEY_4:
      tool_ = Tool::Move;
      break;
    case GLFW_KEY_5:
      tool_ = Tool::Paint;
      break;
    case GLFW_KEY_C:
      cut_painted(v);
      break;
    case GLFW_KEY_K:
      suggest_all_keys(v);
      break;
    case GLFW_KEY_X:
      xray_ = !xray_;
      break;
    case GLFW_KEY_D: {  // the mode switch of the panel, from the keyboard (and replays)
      MergeSetup next = setup();
      auto& o = next.options;
      if (o.mode == mesh_merge::MergeMode::Transition) {  // the bands' boundary condition, §3.3.2 or §3.3.1
        o.transition.configuration_dependent = !o.transition.configuration_dependent;
        commit(v, std::move(next), "transition boundary");
        break;
      }
      const bool dependent = o.mode == mesh_merge::MergeMode::Dependent;
      o.mode = dependent ? mesh_merge::MergeMode::Independent : mesh_merge::MergeMode::Dependent;
      commit(v, std::move(next), "mode");
      break;
    }
    case GLFW_KEY_R:  // optimal mode: the region tool 5 paints, in turn
      if (!optimal_mode()) return false;
      optimal_region_ = (optimal_region_ + 1) % 3, tool_ = Tool::Paint;
      v.flash(std::string("painting the ") + optimal_region_name(optimal_region_));
      break;
    case GLFW_KEY_A:  // independent mode: the region painted on the source becomes a fixed feature (§3.5)
      if (setup().options.mode != mesh_merge::MergeMode::Independent) return false;
      add_painted_feature(v);
      break;
    case GLFW_KEY_T: {  // transition regions (§3.3.3) on / off, as the panel's radio button does
      MergeSetup next = setup();
      auto& o = next.options;
      if (o.mode == mesh_merge::MergeMode::Transition) {
        o.mode = mesh_merge::MergeMode::Independent;
      } else {
        o.mode = mesh_merge::MergeMode::Transition;
        if (!(o.transition.source_width > 0) || !(o.transition.target_width > 0))
          o.transition.source_width = o.transition.target_width = first_band_width(next);
      }
      commit(v, std::move(next), "mode");
      break;
    }
    case GLFW_KEY_M:
      requested_revision_ = 0, request_merge();
      break;  // explicit: even when incomplete
    case GLFW_KEY_TAB:
      show_result_ = !show_result_, scene_dirty_ = true;
      break;
    case GLFW_KEY_F:
      frame(v);
      break;  // before the viewer's own F, which ignores the panels
    case GLFW_KEY_ESCAPE:
      clear_picks();
      break;
    default:
      return false;
  }
  scene_dirty_ = true;
  return true;
}

}  // namespace lapis::merge_app
