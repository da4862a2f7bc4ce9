#pragma once
// A test fixture that hands each test its own scratch file paths in gtest's temp dir (named
// after the test and the process) and deletes them when the test ends.
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

namespace mixtrace::testing {

class ScratchFiles : public ::testing::Test {
 protected:
  std::string tempPath(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    const std::string file = "mixtrace_" + std::string(info->test_suite_name()) + "_" + std::string(info->name()) +
                             "_" + std::to_string(::getpid()) + "_" + name;
    created_.push_back(std::filesystem::path(::testing::TempDir()) / file);
    return created_.back().string();
  }
  void TearDown() override {
    std::error_code ignored;
    for (const auto& path : created_) std::filesystem::remove(path, ignored);
  }

 private:
  std::vector<std::filesystem::path> created_;
};

}  // namespace mixtrace::testing
