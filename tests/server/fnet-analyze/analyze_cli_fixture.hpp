// fnet-analyze run as a process by a test (FNET_ANALYZE names the binary), in a scratch
// directory of the test's own that it may write input files to.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/support/child_process.hpp"
#include "tests/support/temp_dir.hpp"

namespace fnet::testing {

class AnalyzeCliTest : public ::testing::Test {
 protected:
  ProcessResult analyze(const std::vector<std::string>& args) { return run_process(FNET_ANALYZE, args, dir_.path()); }
  std::filesystem::path write(const std::string& name, const std::string& text) { return dir_.write(name, text); }
  const std::filesystem::path& dir() const { return dir_.path(); }

  // Expects exit code `code`, nothing on stdout, and returns stderr.
  std::string fails_with(int code, const std::vector<std::string>& args) {
    const ProcessResult r = analyze(args);
    EXPECT_EQ(r.exit_code, code) << ::testing::PrintToString(args) << "\n" << r.err;
    EXPECT_EQ(r.out, "");
    return r.err;
  }

 private:
  TempDir dir_;
};

}  // namespace fnet::testing
