// Avenues — internal invariants (see check.h).
#include "core/check.h"

#include <filesystem>

namespace avenues {

void invariant_failed(const char* file, int line, const char* cond, const std::string& what) {
  throw InvariantError("internal error (a bug in Avenues, please report it): " + what + " [" + cond + " at " +
                       std::filesystem::path(file).filename().string() + ":" + std::to_string(line) + "]");
}

}  // namespace avenues
