#pragma once
// The cores this process may use: what `--threads auto` takes and what the thread pool spins on
// (worker_threads.hpp). std::thread::hardware_concurrency() counts the machine's cores; a process bound
// to some of them (taskset, numactl, mpirun --bind-to, a batch system) or in a container with a CPU quota
// (cgroup cpu.max) may use fewer, and threads beyond those only wait for each other.
#include <optional>
#include <string>
#include <vector>

namespace dem {

/// min(the CPU affinity mask's count, the cgroup CPU quota rounded up), at least 1.
int usable_cores();

/// A cgroup quota as cpu.max (v2: "QUOTA PERIOD" or "max PERIOD") gives it: QUOTA / PERIOD cores, rounded
/// up; nullopt for "max" (no quota) or text that is not a quota.
std::optional<int> cores_of_quota(const std::string& cpu_max);

/// The smallest quota of several cpu.max texts (the group's, its parents', a v1 quota and period): the
/// one that binds. nullopt when none is a quota.
std::optional<int> smallest_quota_cores(const std::vector<std::string>& cpu_max);

}  // namespace dem
