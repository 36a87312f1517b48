#pragma once
// What a run writes while it runs (run.cpp): a cleared folder (never two runs mixed), summary.json
// saying "running" until the end, the series as series.csv.partial until it is complete, VTK
// snapshots, force-network pictures at the chosen steps, checkpoints; every write checked (OutputError,
// output_files.hpp). With no output folder it writes nothing.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "dem/cases/case_file.hpp"
#include "dem/core/simulation.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/picture/force_network.hpp"
#include "dem/run/quantities.hpp"
#include "dem/run/run.hpp"

namespace dem {

class RunOutputs {
 public:
  /// `series`: the case's output.series compiled (before a restart moves the state).
  RunOutputs(const Case& c, const RunOptions& opt, std::vector<QuantityFn> series);

  /// Clears the folder, writes summary.json ("running") and the series header, and finds the steps
  /// of the pictures (the first step at or after each chosen time) up to `total_steps`.
  void open(const Simulation& sim, std::int64_t total_steps);

  void write_row(const Simulation& sim);   // one series row (when the case has a series) and dump frame
  void snapshot(const Simulation& sim);    // one VTK snapshot (when the case asks for them)
  void contacts(const Simulation& sim);    // the rows of contacts.csv of this step (output.contacts)
  /// A picture if `wanted` or one of the chosen steps is this one (chosen steps passed are dropped).
  void picture(const Simulation& sim, bool wanted);
  bool picture_due(std::int64_t step) const {
    return next_picture_ < picture_steps_.size() && picture_steps_[next_picture_] == step;
  }
  void checkpoint(const Simulation& sim, const std::vector<double>& loop);
  /// The bonds that broke in the last step (output.bond_breaks): rows of bond_breaks.csv, marks on the
  /// pictures from now on.
  void bond_breaks(const Simulation& sim, const std::vector<Simulation::BondBreak>& breaks);

  /// The last row, snapshot and picture (an interrupted run does not repeat the ones of its last step).
  void finish(const Simulation& sim, bool interrupted);
  /// The pictures and checkpoint in the summary; then (if writing) the end-of-run checkpoint, the
  /// series made complete, snapshots.pvd and summary.json.
  void commit(const Simulation& sim, nlohmann::json& summary, bool checkpoint_now, const std::vector<double>& loop);
  /// After an error once the folder is open: summary.json says "failed" with the message (best effort: a
  /// disk too full for it leaves "running", as a killed run does).
  void record_failure(const std::string& message) noexcept;

 private:
  const Case& c_;
  const RunOptions& opt_;
  const bool write_;
  std::vector<QuantityFn> series_;
  StreamedFile csv_;
  StreamedFile dump_;  // dump.lammpstrj (lammps_dump.hpp), a frame with each series row
  std::string row_;
  StreamedFile contacts_;  // contacts.csv (contacts_csv.hpp), the contacts at the chosen steps
  std::int64_t row_step_ = -1, snapshot_step_ = -1, contacts_step_ = -1;  // the step of the last row / snapshot written
  std::vector<std::pair<double, std::string>> snapshots_;
  std::optional<std::int64_t> checkpoint_step_;
  std::vector<std::int64_t> picture_steps_;
  std::size_t next_picture_ = 0;
  std::int64_t picture_step_ = -1;  // the step of the last picture written
  struct Picture {
    double time;
    std::int64_t step;
    std::string file;
  };
  std::vector<Picture> pictures_;
  PictureOptions picture_options_;
  std::string bond_breaks_csv_;  // bond_breaks.csv's rows so far
};

}  // namespace dem
