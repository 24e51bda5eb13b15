// Avenues — numbers in messages and reports: one way to print a double.
#pragma once

#include <string>

namespace avenues {

/// `v` with up to 6 significant digits ("%.6g"): 2.5, 1e+300, nan. For messages.
std::string format_number(double v);

/// `v` by a printf format taking one double ("%.3f"), for tables and reports.
std::string format_number(const char* printf_format, double v);
/// Every bit of v: 17 significant digits, which read back as the same double
/// (eyes and keyframes written for `avenues view` and `path --keys`).
inline std::string format_exact(double v) { return format_number("%.17g", v); }

}  // namespace avenues
