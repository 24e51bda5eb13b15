// Avenues — `avenues generate office --rooms ROWSxCOLS -o FILE.toml`: a plan of an
// office floor with a grid of rooms, for testing and benchmarking at scale.
#include <iostream>
#include <regex>
#include <stdexcept>
#include <string>

#include "app/commands.h"
#include "core/atomic_file.h"
#include "plans/generate.h"

namespace avenues::app {

namespace {
constexpr int kMaxSide = 1000;  // 1000x1000 rooms is already a very large plan
}

int run_generate_office(const GenerateOfficeOptions& opt) {
  static const std::regex pattern("^([0-9]{1,6})x([0-9]{1,6})$");
  std::smatch m;
  if (!std::regex_match(opt.rooms, m, pattern))
    throw std::runtime_error("--rooms: expected ROWSxCOLS, such as 3x4, got '" + opt.rooms + "'");
  int rows = std::stoi(m[1].str()), cols = std::stoi(m[2].str());
  if (rows < 1 || cols < 1 || rows > kMaxSide || cols > kMaxSide)
    throw std::runtime_error("--rooms ROWSxCOLS: each must be between 1 and " + std::to_string(kMaxSide) +
                             ", got '" + opt.rooms + "'");
  std::string toml = generate_office_toml(rows, cols);
  write_file_atomically(opt.output, toml);
  std::cout << "wrote an office of " << rows << "x" << cols << " rooms to " << opt.output << "\n";
  return 0;
}

}  // namespace avenues::app
