// Files and directories for tests: one way to read a file back and to start from an empty directory.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace cleave::test {

namespace fs = std::filesystem;

// The bytes of `f` ("" when it cannot be read: the assertions on its content then say so).
inline std::string read_text(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// `d`, emptied of what an earlier run left there, and created.
inline fs::path fresh_dir(const fs::path& d) {
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A path in the system's temporary directory for the running test: PREFIX, the test's name and the
// process id (CTest runs each test in its own process, concurrently).
inline fs::path per_test_path(const std::string& prefix) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return fs::temp_directory_path() / (prefix + std::string(info->name()) + "_" + std::to_string(::getpid()));
}

}  // namespace cleave::test
