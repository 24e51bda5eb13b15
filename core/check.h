// Avenues — internal invariants (the second of the three tiers of errors, STYLE.md):
// a plan mistake is a PlanError naming the file and line; a broken invariant is a bug in
// Avenues, reported by these macros with the source line that found it; a limit reached
// at run time is a warning.
//
//   AVENUES_CHECK(cond, what)   always evaluated; throws InvariantError when cond is false.
//   AVENUES_DCHECK(cond, what)  evaluated only in builds with invariant checks
//                               (-DAVENUES_INVARIANTS=ON, the default for Debug builds);
//                               otherwise compiled out, cond unevaluated.
// `what` is anything that converts to std::string, built only when the check fails.
#pragma once

#include <stdexcept>
#include <string>

namespace avenues {

/// An internal invariant does not hold: a bug, not bad input.
struct InvariantError : std::logic_error {
  using std::logic_error::logic_error;
};

/// True in builds with invariant checks (AVENUES_DCHECK on, every complex validated).
constexpr bool kInvariantChecks =
#ifdef AVENUES_INVARIANTS
    true;
#else
    false;
#endif

[[noreturn]] void invariant_failed(const char* file, int line, const char* cond, const std::string& what);

}  // namespace avenues

#define AVENUES_CHECK(cond, what)                                              \
  do {                                                                         \
    if (!(cond)) ::avenues::invariant_failed(__FILE__, __LINE__, #cond, (what)); \
  } while (false)

#ifdef AVENUES_INVARIANTS
#define AVENUES_DCHECK(cond, what) AVENUES_CHECK(cond, what)
#else
#define AVENUES_DCHECK(cond, what) \
  do {                             \
  } while (false)
#endif
