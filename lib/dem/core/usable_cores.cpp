#include "dem/core/usable_cores.hpp"

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

namespace dem {

namespace {

std::string read_first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

// The cgroup v2 quota of this process's group (and of the root of the namespace, what a container sees),
// or the v1 cfs quota; the smallest found.
std::optional<int> cgroup_quota_cores() {
  std::vector<std::string> quotas{read_first_line("/sys/fs/cgroup/cpu.max")};
  std::ifstream groups("/proc/self/cgroup");
  for (std::string line; std::getline(groups, line);) {
    if (line.rfind("0::", 0) == 0 && line.size() > 3) quotas.push_back(read_first_line("/sys/fs/cgroup" + line.substr(3) + "/cpu.max"));
  }
  const std::string v1_quota = read_first_line("/sys/fs/cgroup/cpu/cpu.cfs_quota_us");
  const std::string v1_period = read_first_line("/sys/fs/cgroup/cpu/cpu.cfs_period_us");
  if (!v1_quota.empty() && !v1_period.empty()) quotas.push_back(v1_quota + " " + v1_period);
  return smallest_quota_cores(quotas);
}

}  // namespace

std::optional<int> smallest_quota_cores(const std::vector<std::string>& cpu_max) {
  std::optional<int> best;
  for (const std::string& text : cpu_max) {
    const std::optional<int> q = cores_of_quota(text);
    if (q && (!best || *q < *best)) best = q;
  }
  return best;
}

std::optional<int> cores_of_quota(const std::string& cpu_max) {
  std::istringstream in(cpu_max);
  std::string quota;
  double period = 0.0;
  if (!(in >> quota >> period) || quota == "max" || !(period > 0.0)) return std::nullopt;
  char* end = nullptr;
  const double q = std::strtod(quota.c_str(), &end);
  if (end == quota.c_str() || *end != '\0' || !(q > 0.0)) return std::nullopt;  // v1 says -1 for none
  return std::max(1, static_cast<int>(std::ceil(q / period - 1e-9)));
}

int usable_cores() {
  int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) cores = std::max(1, CPU_COUNT(&set));
  if (const auto quota = cgroup_quota_cores()) cores = std::min(cores, *quota);
  return cores;
}

}  // namespace dem
