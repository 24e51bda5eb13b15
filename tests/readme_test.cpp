// Avenues — the README's two set-up commands: CI runs exactly the second one.
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/test_files.h"

using avenues::testing::slurp;

namespace {

/// The lines of the README's ```sh blocks.
std::vector<std::string> sh_commands(const std::string& readme) {
  std::vector<std::string> out;
  std::istringstream in(readme);
  std::string line;
  bool in_sh = false;
  while (std::getline(in, line)) {
    if (line.rfind("```", 0) == 0) {
      in_sh = !in_sh && line == "```sh";
      continue;
    }
    if (in_sh && !line.empty()) out.push_back(line);
  }
  return out;
}

}  // namespace

TEST(Readme, CiRunsTheSecondSetUpCommand) {
  const std::string root = AVENUES_SOURCE_DIR;
  std::vector<std::string> cmds = sh_commands(slurp(root + "/README.md"));
  ASSERT_GE(cmds.size(), 2u) << "README.md should show two set-up commands";
  EXPECT_NE(cmds[0].find("./build/app/avenues"), std::string::npos) << cmds[0];
  EXPECT_NE(cmds[1].find("ctest"), std::string::npos) << cmds[1];
  const std::string run = slurp(root + "/.ci/run");
  EXPECT_NE(run.find("\n" + cmds[1] + "\n"), std::string::npos)
      << ".ci/run must run README's second command verbatim:\n" << cmds[1];
}
