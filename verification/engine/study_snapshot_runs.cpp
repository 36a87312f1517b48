// The snapshot runs of a study (study_snapshots.hpp): each listed variant once more, writing only the
// pictures at the listed times into <study out>/snapshots/<id>/<variant slug>/, or the folder reused
// when the same run wrote it; then result.json's "snapshots" list.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

#include "dem/cases/case_file.hpp"
#include "dem/cases/text.hpp"
#include "dem/run/checkpoint.hpp"
#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"
#include "engine/run_cache.hpp"
#include "engine/study_run.hpp"
#include "engine/study_snapshots.hpp"

namespace fs = std::filesystem;

namespace ver {

namespace {

/// One snapshot run: a variant of a snapshot, its folder and overrides.
struct SnapshotRun {
  const Snapshot* snap = nullptr;
  const Variant* variant = nullptr;
  fs::path folder;                 // absolute: <study out>/snapshots/<id>/<slug>
  std::string relative;            // snapshots/<id>/<slug> (result.json's paths are relative to the study folder)
  std::vector<std::string> sets;   // study, variant, finest level, then the picture overrides
  double dt = 0.0;
  nlohmann::json resolved;         // the resolved case (cache key)
  std::string case_hash;
};

/// The first step at or after time t: the step the run draws the picture of t at (run_outputs.cpp).
std::int64_t step_of(double t, double dt) { return std::llround(std::ceil(t / dt - 1e-9)); }

/// The summary.json of a finished run in `folder`, or null.
nlohmann::json summary_of(const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_regular_file(folder / "summary.json", ec)) return nullptr;
  try {
    nlohmann::json j = nlohmann::json::parse(dem::read_file(folder / "summary.json"));
    if (!j.is_object() || j.value("status", "running") == "running") return nullptr;
    return j;
  } catch (const std::exception&) {
    return nullptr;
  }
}

/// The requested pictures of the run as (at, picture entry of summary.json or null): "end" is the
/// last picture, a time the picture at its step.
std::vector<std::pair<std::string, nlohmann::json>> requested(const SnapshotRun& r, const nlohmann::json& summary) {
  std::map<std::int64_t, nlohmann::json> by_step;
  nlohmann::json last = nullptr;
  if (summary.is_object() && summary.contains("pictures"))
    for (const auto& p : summary["pictures"]) {
      by_step[p.value("step", std::int64_t{-1})] = p;
      last = p;
    }
  std::vector<std::pair<std::string, nlohmann::json>> out;
  for (double t : r.snap->times) {
    const auto it = by_step.find(step_of(t, r.dt));
    out.emplace_back(fmt::format("{:g} s", t), it == by_step.end() ? nlohmann::json(nullptr) : it->second);
  }
  if (r.snap->end) out.emplace_back("end", last);
  return out;
}

/// The folder holds this very run (same resolved case, overrides, code version) with every requested
/// picture on disk, and the run cache knows it: nothing to rerun.
bool reusable(const SnapshotRun& r, const fs::path& entry) {
  if (!read_cached(entry)) return false;
  const nlohmann::json summary = summary_of(r.folder);
  if (summary.is_null() || summary.value("case_hash", "") != r.case_hash ||
      summary.value("overrides", nlohmann::json()) != nlohmann::json(r.sets) ||
      summary.value("provenance", nlohmann::json::object()).value("code_version", "") != dem::provenance().value("code_version", ""))
    return false;
  for (const auto& [at, p] : requested(r, summary))
    if (p.is_null() || !fs::is_regular_file(r.folder / p.value("file", "")))
      return false;
  return true;
}

std::vector<SnapshotRun> plan_runs(const StudyRun& run) {
  const Study& s = run.s;
  std::vector<SnapshotRun> runs;
  for (const Snapshot& snap : s.snapshots) {
    std::map<std::string, int> slugs;  // two labels with one slug get -2, -3, …
    for (const Variant& v : s.variants) {
      if (!snap.variants.empty() && std::find(snap.variants.begin(), snap.variants.end(), v.label) == snap.variants.end())
        continue;
      SnapshotRun r{&snap, &v};
      std::string slug = variant_slug(v.label);
      if (const int k = ++slugs[slug]; k > 1) slug += fmt::format("-{}", k);
      r.relative = fmt::format("snapshots/{}/{}", snap.id, slug);
      r.folder = run.out / r.relative;
      r.sets = s.set;
      r.sets.insert(r.sets.end(), v.set.begin(), v.set.end());
      if (s.kind == Kind::refinement)
        r.sets.insert(r.sets.end(), s.refinement.levels.back().set.begin(), s.refinement.levels.back().set.end());
      const std::vector<std::string> pictures = snapshot_sets(snap);
      r.sets.insert(r.sets.end(), pictures.begin(), pictures.end());
      const dem::Case c = dem::read_case(s.case_file, r.sets);
      r.dt = c.model.numerics.dt;
      r.resolved = c.resolved;
      r.case_hash = dem::case_hash(c);
      runs.push_back(std::move(r));
    }
  }
  return runs;
}

/// Removes the pictures of the run that were not asked for (the first step of a run with "end").
void drop_unrequested(const SnapshotRun& r, const nlohmann::json& summary) {
  std::vector<std::string> keep;
  for (const auto& [at, p] : requested(r, summary))
    if (p.is_object()) keep.push_back(p.value("file", ""));
  if (!summary.is_object() || !summary.contains("pictures")) return;
  std::error_code ec;
  for (const auto& p : summary["pictures"])
    if (std::find(keep.begin(), keep.end(), p.value("file", "")) == keep.end()) fs::remove(r.folder / p.value("file", ""), ec);
}

/// result.json's entries of one run.
void list_pictures(const SnapshotRun& r, const RunOut& out, nlohmann::json& list) {
  const nlohmann::json summary = summary_of(r.folder);
  for (const auto& [at, p] : requested(r, summary)) {
    nlohmann::json e = {{"id", r.snap->id}, {"title", r.snap->title}, {"variant", r.variant->label}, {"at", at},
                        {"max_force", r.snap->max_force ? nlohmann::json(*r.snap->max_force) : nlohmann::json(nullptr)}};
    if (p.is_object() && fs::is_regular_file(r.folder / p.value("file", ""))) {
      e["time"] = p.value("time", 0.0);
      e["step"] = p.value("step", std::int64_t{-1});
      e["file"] = r.relative + "/" + p.value("file", "");
    } else {
      e["time"] = nullptr;
      e["step"] = nullptr;
      e["file"] = nullptr;
      e["note"] = fmt::format("no picture: the run ended ({}{}) before {}", out.status,
                              out.message.empty() ? "" : ": " + out.message, at);
    }
    list.push_back(e);
  }
}

/// Removes whatever snapshots/ holds besides the planned run folders (a snapshot or variant no longer
/// declared, a folder of an earlier slug): the study folder holds no picture that result.json does not list.
void remove_undeclared(const fs::path& root, const std::vector<SnapshotRun>& runs) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return;
  std::set<fs::path> ids, folders;
  for (const SnapshotRun& r : runs) {
    ids.insert(r.folder.parent_path());
    folders.insert(r.folder);
  }
  std::vector<fs::path> gone;  // collected first: nothing removed while a folder is being listed
  for (const auto& id : fs::directory_iterator(root, ec)) {
    if (!ids.count(id.path())) {
      gone.push_back(id.path());
      continue;
    }
    for (const auto& f : fs::directory_iterator(id.path(), ec))
      if (!folders.count(f.path())) gone.push_back(f.path());
  }
  for (const fs::path& p : gone) fs::remove_all(p, ec);
}

}  // namespace

nlohmann::json take_snapshots(StudyRun& run) {
  nlohmann::json list = nlohmann::json::array();
  std::vector<SnapshotRun> runs = plan_runs(run);
  remove_undeclared(run.out / "snapshots", runs);
  if (runs.empty()) {
    std::error_code ec;
    fs::remove(run.out / "snapshots", ec);  // empty by now
    return list;
  }
  std::vector<RunOut> outs(runs.size());
  std::vector<Planned> plan;
  std::vector<std::size_t> slot;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const fs::path entry = cache_entry(run.cache_dir, runs[k].resolved, runs[k].sets, runs[k].folder);
    if (run.opt.use_cache && reusable(runs[k], entry)) {
      const CachedRun cached = *read_cached(entry);
      ++run.reused;
      run.note_reused(cached, 0.0);
      outs[k] = {cached.probes, cached.status, cached.message, cached.eps, cached.seconds_per_step};
      continue;
    }
    std::error_code ec;
    fs::remove_all(runs[k].folder, ec);  // never an earlier run's picture beside this run's
    plan.push_back({runs[k].sets, runs[k].folder});
    slot.push_back(k);
  }
  if (!plan.empty()) {
    std::vector<RunOut> done = run.run_many(plan, run.opt.jobs);
    for (std::size_t i = 0; i < done.size(); ++i) {
      outs[slot[i]] = std::move(done[i]);
      drop_unrequested(runs[slot[i]], summary_of(runs[slot[i]].folder));
    }
  }
  for (std::size_t k = 0; k < runs.size(); ++k) list_pictures(runs[k], outs[k], list);
  return list;
}

}  // namespace ver
