// tests/process_tmpdir.cpp: the temporary folder of a test process is its own.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>

TEST_CASE("A test process has a temporary folder of its own - parallel runs never share scratch paths", "[tests]") {
  const std::filesystem::path tmp = std::filesystem::temp_directory_path();
  INFO(tmp.string());
  CHECK(tmp.filename().string().rfind("dem2d_test_", 0) == 0);
  CHECK(std::filesystem::is_directory(tmp));
  const char* env = std::getenv("TMPDIR");
  REQUIRE(env != nullptr);
  CHECK(std::filesystem::path(env) == tmp);
}
