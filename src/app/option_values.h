// Numeric command-line values read as text and checked here, so that every absurd value is refused with a
// message naming the option and the allowed range: CLI11 takes "nan" and "inf" as numbers and turns an
// integer that overflows into the largest one.
#pragma once

#include <stdexcept>
#include <string>

namespace sph {

// A command-line value outside what an option allows (exit status 1).
struct OptionError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// text as a finite number in [lo, hi], or (lo, hi] when lo_open. Throws OptionError naming option and
// the range, for example "--time: \"nan\" is not a finite number; allowed (0, 1e+07] seconds".
double finite_option(const std::string& option, const std::string& text, double lo, double hi, bool lo_open,
                     const std::string& unit);

// text as a whole number in [lo, hi] (an optional sign and digits, no exponent). Throws OptionError.
long long whole_option(const std::string& option, const std::string& text, long long lo, long long hi);

}  // namespace sph
