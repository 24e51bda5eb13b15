// Avenues — the one place where the command line's values are checked.
//
// Every numeric option is checked for finiteness and range here, and every option with a
// fixed set of words or a format (--kernel, --samples, --size WxH, an output FILE) has its
// rule here once. cli.cpp attaches the checks to the options as CLI11 validators, so a bad
// value is refused while parsing ("--fov: ... not nan", exit status 2); the subcommands
// turn the same strings into values with the same functions, which throw
// std::runtime_error naming the option.
#pragma once

#include <string>

#include "render/lighting.h"
#include "visibility/visible_set.h"

namespace CLI {
class Validator;
}

namespace avenues::app {

/// A finite number in [lo, hi] (or (lo, hi] with `open_low`); nan and inf are refused.
CLI::Validator number_in(double lo, double hi, bool open_low = false);
/// Any finite number.
CLI::Validator finite_number();
/// A finite number > 0.
CLI::Validator positive_number();
/// A whole number >= lo.
CLI::Validator whole_at_least(long lo);
/// An output file name: not empty (an empty name would silently write nothing).
CLI::Validator file_name();
/// The checks below, as validators.
CLI::Validator kernel_name();
CLI::Validator samples_count();
CLI::Validator size_wxh();

/// --kernel: float, double, filtered or exact. Throws naming `option` otherwise.
Kernel kernel_option(const std::string& s, const char* option = "--kernel");
/// --search: merged (the avenues into a cell joined where their union is convex, the
/// default) or jones (Jones's tree of avenues, one per chain of portals), in `kernel`.
TraverseParams search_option(const std::string& s, Kernel kernel, const char* option = "--search");
CLI::Validator search_name();
/// --lights: plan or eye. Throws naming `option` otherwise.
Lights lights_option(const std::string& s, const char* option = "--lights");
/// --object-shadows: auto, on or off. Throws naming `option` otherwise.
ObjectShadows object_shadows_option(const std::string& s, const char* option = "--object-shadows");
/// --samples: half-tone samples per pixel, 1, 4 or 16. Throws naming `option` otherwise.
int samples_option(int samples, const char* option = "--samples");
/// --size WxH in pixels, each 1..32768. Throws naming `option` otherwise.
void size_option(const std::string& s, int& w, int& h, const char* option = "--size");
/// "WxH" in pixels, each 1..32768: false when `s` is not that.
bool parse_size(const std::string& s, int& w, int& h);

}  // namespace avenues::app
