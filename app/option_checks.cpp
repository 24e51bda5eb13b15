// Avenues — the one place where the command line's values are checked (app/option_checks.h).
#include "app/option_checks.h"

#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "core/number_format.h"

namespace avenues::app {
namespace {

/// `s` as a whole finite number, or false.
bool number_of(const std::string& s, double& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

}  // namespace

CLI::Validator number_in(double lo, double hi, bool open_low) {
  const std::string range = std::string(open_low ? "(" : "[") + format_number(lo) + ", " + format_number(hi) + "]";
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        double v = 0;
        if (!number_of(s, v) || !std::isfinite(v)) return "wants a finite number, not '" + s + "'";
        if (v < lo || v > hi || (open_low && v == lo)) return "must lie in " + range + ", not " + s;
        return {};
      },
      "NUMBER in " + range);
}

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        double v = 0;
        return number_of(s, v) && std::isfinite(v) ? std::string() : "wants a finite number, not '" + s + "'";
      },
      "NUMBER");
}

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        double v = 0;
        if (!number_of(s, v) || !std::isfinite(v)) return "wants a finite number, not '" + s + "'";
        if (!(v > 0)) return "must be greater than 0, not " + s;
        return {};
      },
      "NUMBER > 0");
}

CLI::Validator whole_at_least(long lo) {
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        char* end = nullptr;
        errno = 0;
        const long v = s.empty() ? 0 : std::strtol(s.c_str(), &end, 10);
        if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE) return "wants a whole number, not '" + s + "'";
        if (v < lo) return "must be at least " + std::to_string(lo) + ", not " + s;
        return {};
      },
      "INT >= " + std::to_string(lo));
}

CLI::Validator file_name() {
  return CLI::Validator(
      [](std::string& s) -> std::string { return s.empty() ? "wants a file name, not an empty one" : std::string(); },
      "FILE");
}

Kernel kernel_option(const std::string& s, const char* option) {
  Kernel k = Kernel::Double;
  if (!parse_kernel(s, k))
    throw std::runtime_error(std::string(option) + " wants float, double, filtered or exact, not '" + s + "'");
  return k;
}

TraverseParams search_option(const std::string& s, Kernel kernel, const char* option) {
  TraverseParams p;
  p.kernel = kernel;
  if (s == "merged") p.merge_pieces = true;
  else if (s == "hull") p.merge_pieces = p.hull_pieces = true;
  else if (s != "jones") throw std::runtime_error(std::string(option) + " wants merged, hull or jones, not '" + s + "'");
  return p;
}

Lights lights_option(const std::string& s, const char* option) {
  Lights l = Lights::Plan;
  if (!parse_lights(s, l)) throw std::runtime_error(std::string(option) + " wants plan or eye, not '" + s + "'");
  return l;
}

ObjectShadows object_shadows_option(const std::string& s, const char* option) {
  ObjectShadows o = ObjectShadows::Auto;
  if (!parse_object_shadows(s, o))
    throw std::runtime_error(std::string(option) + " wants auto, on or off, not '" + s + "'");
  return o;
}

int samples_option(int samples, const char* option) {
  if (samples != 1 && samples != 4 && samples != 16)
    throw std::runtime_error(std::string(option) + " wants 1, 4 or 16, not " + std::to_string(samples));
  return samples;
}

bool parse_size(const std::string& s, int& w, int& h) {
  size_t x = s.find('x');
  if (x == std::string::npos) return false;
  try {
    size_t a = 0, b = 0;
    w = std::stoi(s.substr(0, x), &a);
    h = std::stoi(s.substr(x + 1), &b);
    return a == x && b == s.size() - x - 1 && w > 0 && h > 0 && w <= 32768 && h <= 32768;
  } catch (const std::exception&) {
    return false;
  }
}

void size_option(const std::string& s, int& w, int& h, const char* option) {
  if (!parse_size(s, w, h))
    throw std::runtime_error(std::string(option) + " wants WIDTHxHEIGHT in pixels (each 1 to 32768), not '" + s + "'");
}

namespace {
/// A validator from one of the throwing checks above: its message, less the option's name
/// (CLI11 puts the name in front).
template <class Check>
CLI::Validator from_check(Check check, const char* desc) {
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        try {
          check(s);
        } catch (const std::runtime_error& e) {
          std::string m = e.what();
          const size_t space = m.find(' ');
          return space == std::string::npos ? m : m.substr(space + 1);
        }
        return {};
      },
      desc);
}
}  // namespace

CLI::Validator kernel_name() {
  return from_check([](const std::string& s) { kernel_option(s); }, "float|double|filtered|exact");
}

CLI::Validator search_name() {
  return from_check([](const std::string& s) { search_option(s, Kernel::Double); }, "merged|hull|jones");
}

CLI::Validator samples_count() {
  return from_check(
      [](const std::string& s) {
        char* end = nullptr;
        const long v = std::strtol(s.c_str(), &end, 10);
        if (s.empty() || end != s.c_str() + s.size() || (v != 1 && v != 4 && v != 16))
          throw std::runtime_error("--samples wants 1, 4 or 16, not " + s);
      },
      "1|4|16");
}

CLI::Validator size_wxh() {
  return from_check(
      [](const std::string& s) {
        int w = 0, h = 0;
        size_option(s, w, h);
      },
      "WxH");
}

}  // namespace avenues::app
