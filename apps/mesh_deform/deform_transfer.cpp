// The deform app's deformation transfer (Au et al. 2007, §6): a target mesh opened beside the
// edited one, one click on it per source handle (Tool::Pair), and every solved frame carried
// onto it by a DeformationTransfer on its own worker, so the source's drag never waits for it.
#include <chrono>
#include <nlohmann/json.hpp>

#include "deform_app.h"
#include "lapis/core/atomic_file.h"
#include "lapis/geometry/io.h"
#include "lapis/mesh_deform/selection_io.h"
#include "lapis/viewer/picking.h"

namespace lapis::deform_app {

void DeformApp::open_transfer_target(viewer::Viewer& v, const fs::path& path) {
  try {
    geometry::TriMesh target = geometry::read_mesh(path);
    geometry::require_valid(target, {}, path.string());
    pairing_.emplace(std::move(target));
    target_path_ = path;
    target_placement_ = place_beside(rest_, pairing_->target());
    transfer_slot_ = std::make_shared<TransferSlot>(rest_, pairing_->target());
    ++target_epoch_;
    transferred_.reset();
    transfer_error_.clear();
    transfer_received_ = transfer_submitted_;
    target_shown_ = target_placement_.apply(pairing_->target().V);
    target_bvh_.reset();
    target_pick_stale_ = target_dirty_ = true;
    active_pair_ = 0;
    transfer_source_changed();
    tool_ = Tool::Pair;
    update_target_surface(v);
    v.frame_scene();
    v.flash("opened target " + path.string() + ": click where each handle is on it (pair tool, P)",
            viewer::Tone::Success);
  } catch (const Error& e) {
    v.flash(std::string("open target failed: ") + e.what(), viewer::Tone::Error);
  }
}

void DeformApp::close_transfer_target(viewer::Viewer& v) {
  pairing_.reset();
  transfer_slot_.reset();
  transferred_.reset();
  transfer_error_.clear();
  ++target_epoch_;
  transfer_received_ = transfer_submitted_;
  if (tool_ == Tool::Pair) tool_ = Tool::Move;
  v.scene().meshes.erase("transfer target");
  v.scene().points.erase("transfer seeds");
}

void DeformApp::transfer_source_changed() {
  if (!pairing_ || !selection_) return;
  pairing_->set_source(rest_, *conn_, selection_->selection, selection_->handle_label);
  if (const int next = pairing_->next_unplaced(); next >= 0) active_pair_ = next;
  active_pair_ = std::min(active_pair_, static_cast<int>(pairing_->slots().size()) - 1);
  target_dirty_ = true;
}

bool DeformApp::pair_at(viewer::Viewer& v, const Eigen::Vector2d& p) {
  if (!pairing_) return v.flash("pair: open a transfer target first (Transfer panel)"), true;
  if (pairing_->slots().empty()) return v.flash("pair: paint a handle on the mesh first"), true;
  if (!target_bvh_ || target_pick_stale_) {
    geometry::TriMesh shown{target_shown_, pairing_->target().F};
    target_bvh_ = std::make_unique<geometry::Bvh>(shown);
    target_pick_stale_ = false;
  }
  const auto hit = viewer::pick(*target_bvh_, v.camera_matrices(), p.x(), p.y());
  if (!hit) return v.flash("pair: click on the target mesh (the one on the right)"), true;
  const int vertex = viewer::nearest_corner(pairing_->target(), *hit);
  const int slot = std::clamp(active_pair_, 0, static_cast<int>(pairing_->slots().size()) - 1);
  pairing_->place(slot, vertex);
  const PairSlot& s = pairing_->slots()[static_cast<size_t>(slot)];
  if (!s.problem.empty())
    v.flash(s.name + ": " + s.problem);
  else if (!s.placed())
    v.flash(s.name + ": part " + std::to_string(s.seeds.size()) + " of " + std::to_string(s.parts()) +
            " placed, click the next");
  else
    v.flash(s.name + " placed on the target (" + std::to_string(s.region.size()) + " vertices)");
  // On to the next slot to place once this one has all its parts.
  if (const int next = pairing_->next_unplaced(); s.placed() && next >= 0) active_pair_ = next;
  target_dirty_ = true;
  return true;
}

void DeformApp::request_transfer() {
  // The newest frame, solved for the selection the pairs were made from.
  if (!pairing_ || !pairing_->complete() || !last_ || last_->revision != selection_revision_ || last_->epoch != epoch_)
    return;
  if (last_->request == transfer_source_request_ && pairing_->revision() == transfer_pairing_revision_) return;
  transfer_source_request_ = last_->request;
  transfer_pairing_revision_ = pairing_->revision();
  const std::uint64_t id = ++transfer_submitted_, epoch = target_epoch_, source_request = last_->request,
                      revision = pairing_->revision();
  auto slot = transfer_slot_;
  auto source_selection = last_->selection;
  geometry::Vertices pose = last_->frame.positions;
  transfer_worker_.submit([slot, source_selection, target_selection = pairing_->selection(), pose = std::move(pose), id,
                           epoch, source_request, revision] {
    const auto start = std::chrono::steady_clock::now();
    if (!slot->transfer || slot->pairing_revision != revision) {
      slot->transfer.reset();
      slot->transfer =
          std::make_unique<DeformationTransfer>(slot->source, *source_selection, slot->target, target_selection);
      slot->pairing_revision = revision;
    }
    Transferred t;
    t.request = id, t.epoch = epoch, t.source_request = source_request, t.pairing_revision = revision;
    t.positions = slot->transfer->transfer(pose);
    t.report = slot->transfer->report();
    t.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return t;
  });
}

void DeformApp::receive_transfer(viewer::Viewer& v) {
  std::optional<Transferred> t;
  try {
    t = transfer_worker_.take();
  } catch (const Error& e) {
    transfer_error_ = e.what();
    transfer_received_ = transfer_submitted_;
    v.flash(std::string("transfer failed: ") + e.what(), viewer::Tone::Error);
    return;
  }
  if (!t || t->epoch != target_epoch_) return;
  transfer_error_.clear();
  transfer_received_ = t->request;
  target_shown_ = target_placement_.apply(t->positions);
  transferred_ = std::move(t);
  target_pick_stale_ = target_dirty_ = true;
}

bool DeformApp::transfer_ready() const {
  if (!pairing_ || !pairing_->complete() || !last_) return true;
  if (transfer_worker_.busy() || transfer_received_ != transfer_submitted_) return false;
  if (!transfer_error_.empty()) return true;  // the export goes ahead without the target
  return transferred_ && transferred_->source_request == last_->request &&
         transferred_->pairing_revision == pairing_->revision();
}

bool DeformApp::export_transfer(const fs::path& stem, const fs::path& source_out, nlohmann::json& j) {
  if (!pairing_ || !pairing_->complete() || !transferred_ || transferred_->source_request != last_->request)
    return false;
  const std::string base = stem.string() + ".target";
  const fs::path mesh = base + source_out.extension().string(), roi = base + ".roi.txt",
                 handles = base + ".handles.json";
  geometry::TriMesh result = pairing_->target();
  result.V = transferred_->positions;
  geometry::write_mesh(mesh, result);
  const Selection s = pairing_->selection();
  write_roi(roi, s.roi);
  write_handles(handles, s, {HandleTransforms::identity(s)});
  const std::string cli = "lapis transfer --source " + paths_.mesh.string() + " --source-deformed " +
                          source_out.string() + " --source-handles " + j["handles"].get<std::string>() +
                          " --source-roi " + j["roi"].get<std::string>() + " --target " + target_path_.string() +
                          " --target-handles " + handles.string() + " --target-roi " + roi.string() + " --out OUT.obj";
  j["transfer"] = {{"target", target_path_.string()},
                   {"target_roi", roi.string()},
                   {"target_handles", handles.string()},
                   {"out", mesh.string()},
                   {"eq11_residual", transferred_->report.eq11_residual},
                   {"eq12_residual", transferred_->report.eq12_residual},
                   {"cli", cli}};
  return true;
}

}  // namespace lapis::deform_app
