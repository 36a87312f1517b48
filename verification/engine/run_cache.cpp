#include "engine/run_cache.hpp"

#include <fmt/format.h>

#include "dem/run/output_files.hpp"
#include "dem/run/run.hpp"

namespace ver {

std::uint64_t fnv1a(std::string_view text, std::uint64_t h) {
  for (unsigned char ch : text) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

const std::string& code_identity() {
  static const std::string id = [] {
    std::string exe;
    try {
      exe = dem::read_file("/proc/self/exe");
    } catch (const std::exception&) {
    }
    return fmt::format("{}+{:016x}", dem::provenance()["code_version"].get<std::string>(), fnv1a(exe));
  }();
  return id;
}

std::filesystem::path cache_entry(const std::filesystem::path& dir, const nlohmann::json& resolved_case,
                                  const std::vector<std::string>& sets, const std::filesystem::path& out) {
  std::string key = code_identity() + "\n" + resolved_case.dump() + "\n" + out.string();
  for (const auto& x : sets) key += "\n" + x;
  return dir / fmt::format("{:016x}.json", fnv1a(key));
}

std::optional<CachedRun> read_cached(const std::filesystem::path& entry) {
  if (!std::filesystem::exists(entry)) return std::nullopt;
  try {
    const nlohmann::json j = nlohmann::json::parse(dem::read_file(entry));
    CachedRun r{j.at("status").get<std::string>(), j.at("message").get<std::string>(), j.value("eps", 0.0), {}};
    for (const auto& [k, v] : j.at("probes").items())
      r.probes[k] = v.is_null() ? std::nullopt : std::optional<double>(v.get<double>());
    if (const auto p = j.find("provenance"); p != j.end() && p->is_object()) {
      r.code_version = p->value("code_version", "");
      r.date = p->value("date", "");
    }
    r.seconds_per_step = j.value("seconds_per_step", 0.0);
    return r;
  } catch (const std::exception&) {
    return std::nullopt;  // unreadable: run again
  }
}

void write_cached(const std::filesystem::path& entry, const CachedRun& run, const std::string& case_path,
                  const std::vector<std::string>& sets) {
  nlohmann::json probes = nlohmann::json::object();
  for (const auto& [k, v] : run.probes) probes[k] = v ? nlohmann::json(*v) : nlohmann::json(nullptr);
  dem::write_file_atomic(entry, nlohmann::json{{"status", run.status}, {"message", run.message}, {"eps", run.eps},
                                               {"seconds_per_step", run.seconds_per_step},
                                               {"probes", probes}, {"case", case_path}, {"overrides", sets},
                                               {"code", code_identity()}, {"provenance", dem::provenance()}}
                                    .dump() + "\n", false);
}

void mark_running(const std::filesystem::path& out, const std::string& study) {
  dem::write_file_atomic(out / "running.json", nlohmann::json{{"study", study}, {"status", "running"},
                                                              {"provenance", dem::provenance()}}.dump(2) + "\n");
}

void mark_ended(const std::filesystem::path& out, const std::string& study, const std::string& status,
                const std::string& message) {
  try {  // best effort: the error being reported matters more than this note (a full disk)
    dem::write_file_atomic(out / "running.json", nlohmann::json{{"study", study}, {"status", status}, {"message", message},
                                                                {"provenance", dem::provenance()}}.dump(2) + "\n");
  } catch (const std::exception&) {
  }
}

std::filesystem::path open_study_folder(const std::string& study, const StudyOptions& opt) {
  const std::filesystem::path out = opt.out_dir.empty() ? std::filesystem::path("build/studies") / study : opt.out_dir;
  std::filesystem::create_directories(out);
  std::filesystem::remove(out / "result.json");
  mark_running(out, study);
  return out;
}

}  // namespace ver
