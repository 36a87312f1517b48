#pragma once
// Study options for engine tests: one run slot, nothing printed, results in `out`.
#include <filesystem>

#include "engine/study.hpp"

namespace test {

inline ver::StudyOptions quiet_options(const std::filesystem::path& out) {
  ver::StudyOptions o;
  o.out_dir = out;
  o.jobs = 1;
  o.print = false;
  return o;
}

}  // namespace test
