// Avenues — numbers in messages and reports (core/number_format.h).
#include "core/number_format.h"

#include <cstdio>

namespace avenues {

std::string format_number(const char* printf_format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return buf;
}

std::string format_number(double v) { return format_number("%.6g", v); }

}  // namespace avenues
