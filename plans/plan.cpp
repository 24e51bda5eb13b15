// Avenues — the small out-of-line pieces of plan.h: how a source location prints,
// and the names of opening kinds. The reader itself is plan_reader.cpp.
#include "plans/plan.h"

namespace avenues {

// "house.toml:12:3 (wall 'north')", leaving out whatever is unknown: a generated plan
// has no file and no line, so its elements print as just "(wall 'north')" → "wall 'north'".
std::string SourceLoc::str() const {
  std::string s = file;
  if (line > 0) {
    if (!s.empty()) s += ':';
    s += std::to_string(line);
    if (column > 0) s += ':' + std::to_string(column);
  }
  if (!element.empty()) s += s.empty() ? element : " (" + element + ")";
  return s;
}

// The spelling used in plan files (`kind = "door"`), so messages can quote it back.
const char* to_string(OpeningKind k) {
  switch (k) {
    case OpeningKind::Door: return "door";
    case OpeningKind::Window: return "window";
    case OpeningKind::Hatch: return "hatch";
    case OpeningKind::Gap: return "gap";
  }
  return "?";
}

}  // namespace avenues
