#include "dem/run/run_outputs.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "dem/cases/text.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/contacts_csv.hpp"
#include "dem/run/lammps_dump.hpp"
#include "dem/run/vtk_writer.hpp"
#include "dem/run/wall_contacts_csv.hpp"

namespace dem {

RunOutputs::RunOutputs(const Case& c, const RunOptions& opt, std::vector<QuantityFn> series)
    : c_(c),
      opt_(opt),
      write_(!opt.out_dir.empty()),
      series_(std::move(series)),
      picture_options_{static_cast<int>(c.output.picture_width), c.output.picture_max_force, 0.0} {}

void RunOutputs::open(const Simulation& sim, std::int64_t total_steps) {
  const OutputSpec& o = c_.output;
  if (write_) {
    prepare_run_folder(opt_.out_dir);
    write_file_atomic(opt_.out_dir / "summary.json",
                      nlohmann::json{{"case", c_.path.string()}, {"overrides", c_.overrides}, {"provenance", provenance()},
                                     {"status", "running"}, {"case_hash", case_hash(c_)}}
                              .dump(2) + "\n");
    if (!series_.empty()) {
      csv_.open(opt_.out_dir / "series.csv");
      // one header line, each column with its unit ("t [s]"): pandas.read_csv reads it with its
      // defaults; the case and the code version are in summary.json
      std::string head;
      for (std::size_t k = 0; k < series_.size(); ++k) head += (k ? "," : "") + csv_field(series_header(o.series[k]));
      csv_.write(head + "\n");
    }
    if (o.lammps_dump) dump_.open(opt_.out_dir / "dump.lammpstrj");
    if (o.contacts) {
      contacts_.open(opt_.out_dir / "contacts.csv");
      contacts_.write(contacts_csv_header());
    }
    if (o.vtk) std::filesystem::create_directories(opt_.out_dir / "vtk");
    if (o.any_pictures()) std::filesystem::create_directories(opt_.out_dir / "pictures");
  }
  // Force-network pictures: the steps of the chosen times (the first step at or after each time).
  if (write_ && o.any_pictures()) {
    const double dt = sim.model().numerics.dt;
    auto step_of = [&](double t) { return std::llround(std::ceil(t / dt - 1e-9)); };
    if (o.picture_every > 0.0)
      for (std::int64_t n = 1;; ++n) {
        const std::int64_t k = step_of(static_cast<double>(n) * o.picture_every);
        if (k > total_steps) break;
        picture_steps_.push_back(k);
      }
    for (double t : o.picture_times)
      if (step_of(t) <= total_steps) picture_steps_.push_back(step_of(t));
    std::sort(picture_steps_.begin(), picture_steps_.end());
    picture_steps_.erase(std::unique(picture_steps_.begin(), picture_steps_.end()), picture_steps_.end());
  }
  next_picture_ = static_cast<std::size_t>(
      std::lower_bound(picture_steps_.begin(), picture_steps_.end(), sim.steps()) - picture_steps_.begin());
}

void RunOutputs::record_failure(const std::string& message) noexcept {
  if (!write_) return;
  try {
    write_file_atomic(opt_.out_dir / "summary.json",
                      nlohmann::json{{"case", c_.path.string()}, {"overrides", c_.overrides}, {"provenance", provenance()},
                                     {"status", "failed"}, {"message", message}, {"case_hash", case_hash(c_)}}
                              .dump(2) + "\n");
  } catch (...) {
  }
}

void RunOutputs::write_row(const Simulation& sim) {
  if (dump_.is_open()) {
    row_step_ = sim.steps();
    dump_.write(lammps_dump_frame(sim));
  }
  if (!csv_.is_open()) return;
  row_step_ = sim.steps();
  row_.clear();
  for (std::size_t k = 0; k < series_.size(); ++k) {
    if (k) row_ += ',';
    row_ += fmt::format("{:.17g}", series_[k](sim));
  }
  row_ += '\n';
  csv_.write(row_);
}

void RunOutputs::checkpoint(const Simulation& sim, const std::vector<double>& loop) {
  if (!write_) return;
  write_checkpoint(opt_.out_dir / "checkpoint.bin", sim, c_, loop);
  checkpoint_step_ = sim.steps();
}

void RunOutputs::snapshot(const Simulation& sim) {
  if (!write_ || !c_.output.vtk) return;
  snapshot_step_ = sim.steps();
  const std::string name = fmt::format("snapshot_{:09d}.vtp", sim.steps());
  write_vtp(opt_.out_dir / "vtk" / name, sim);
  snapshots_.emplace_back(sim.time(), "vtk/" + name);
}

void RunOutputs::contacts(const Simulation& sim) {
  if (!contacts_.is_open() || contacts_step_ == sim.steps()) return;
  contacts_step_ = sim.steps();
  contacts_.write(contacts_csv_rows(sim));
}

void RunOutputs::picture(const Simulation& sim, bool wanted) {
  while (next_picture_ < picture_steps_.size() && picture_steps_[next_picture_] <= sim.steps()) {
    wanted = wanted || picture_steps_[next_picture_] == sim.steps();
    ++next_picture_;
  }
  if (!wanted || !write_ || picture_step_ == sim.steps()) return;
  picture_step_ = sim.steps();
  const std::string name = fmt::format("picture_{:09d}.png", sim.steps());
  write_force_network_png(opt_.out_dir / "pictures" / name, sim, picture_options_);
  pictures_.push_back({sim.time(), sim.steps(), "pictures/" + name});
}

void RunOutputs::bond_breaks(const Simulation& sim, const std::vector<Simulation::BondBreak>& breaks) {
  const Elements& e = sim.model().elements;
  for (const auto& b : breaks) {
    const std::string other = b.wall ? csv_field(sim.model().walls[b.j].name)
                                     : fmt::format("{}", e.id.empty() ? b.j : e.id[b.j]);
    bond_breaks_csv_ += fmt::format("{:.17g},{},{},{},{},{:.17g},{:.17g},{:.17g},tension (M8)\n", sim.time(), sim.steps(),
                                    e.id.empty() ? b.i : e.id[b.i], other, b.segment, b.xi, b.point.x, b.point.y);
    picture_options_.broken_bonds.push_back(b.point);
  }
}

void RunOutputs::finish(const Simulation& sim, bool interrupted) {
  if (!(interrupted && row_step_ == sim.steps())) write_row(sim);
  if (!(interrupted && snapshot_step_ == sim.steps())) snapshot(sim);
  contacts(sim);  // once per step (contacts_step_)
  picture(sim, c_.output.pictures);
}

void RunOutputs::commit(const Simulation& sim, nlohmann::json& summary, bool checkpoint_now,
                        const std::vector<double>& loop) {
  if (!pictures_.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const Picture& p : pictures_) list.push_back({{"time", p.time}, {"step", p.step}, {"file", p.file}});
    summary["pictures"] = list;
  }
  if (!write_) return;
  if (checkpoint_now) checkpoint(sim, loop);
  if (checkpoint_step_) summary["checkpoint"] = {{"file", "checkpoint.bin"}, {"step", *checkpoint_step_}};
  csv_.commit();
  if (dump_.is_open()) dump_.commit();
  if (contacts_.is_open()) contacts_.commit();
  if (c_.output.vtk) write_pvd(opt_.out_dir / "snapshots.pvd", snapshots_);
  if (!c_.output.wall_contacts.empty()) write_file_atomic(opt_.out_dir / "wall_contacts.csv", wall_contacts_csv(sim, c_.output));
  if (c_.output.bond_breaks)
    write_file_atomic(opt_.out_dir / "bond_breaks.csv",
                      "t [s],step,element,other,segment,xi,x [m],y [m],mode\n" + bond_breaks_csv_);
  write_file_atomic(opt_.out_dir / "summary.json", summary.dump(2) + "\n");
}

}  // namespace dem
