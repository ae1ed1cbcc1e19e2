#include "option_values.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace sph {

double finite_option(const std::string& option, const std::string& text, double lo, double hi, bool lo_open,
                     const std::string& unit) {
  std::ostringstream allowed;
  allowed << "allowed " << (lo_open ? "(" : "[") << lo << ", " << hi << "]" << (unit.empty() ? "" : " " + unit);
  char* end = nullptr;
  const double x = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0')
    throw OptionError(option + ": \"" + text + "\" is not a number; " + allowed.str());
  if (!std::isfinite(x)) throw OptionError(option + ": \"" + text + "\" is not a finite number; " + allowed.str());
  if (x < lo || (lo_open && x == lo) || x > hi)
    throw OptionError(option + ": " + text + " is out of range; " + allowed.str());
  return x;
}

long long whole_option(const std::string& option, const std::string& text, long long lo, long long hi) {
  const std::string allowed = "allowed whole numbers in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  const std::size_t digits = text.find_first_not_of("+-") == 1 ? 1 : 0;  // one optional sign
  if (text.size() == digits || text.find_first_not_of("0123456789", digits) != std::string::npos) {
    // "1e13" is a whole number written as a float: say whether it is out of range rather than not whole.
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (!text.empty() && *end == '\0' && std::isfinite(x) && x == std::floor(x) && (x < double(lo) || x > double(hi)))
      throw OptionError(option + ": " + text + " is out of range; " + allowed);
    throw OptionError(option + ": \"" + text + "\" is not a whole number (write it with digits only); " + allowed);
  }
  errno = 0;
  const long long n = std::strtoll(text.c_str(), nullptr, 10);
  if (errno == ERANGE || n < lo || n > hi) throw OptionError(option + ": " + text + " is out of range; " + allowed);
  return n;
}

}  // namespace sph
