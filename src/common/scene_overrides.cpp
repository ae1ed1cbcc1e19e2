// The command line's --set key=value overrides of a scene file (sph_run --set, tests' scene_file): applied to
// the parsed JSON before it is read, and traced back when the reader refuses a key they wrote.
#include "scene_overrides.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "scene.h"

namespace sph {

using json = nlohmann::json;

namespace {

// The value of "key=value": JSON, or else a number as strtod reads it ("+1", ".5", "1e400"), or else the
// text as a string. A number that is not a finite double ("1e400", "nan", "inf") is refused: taken as a
// string it would only be reported as the wrong type.
json override_value(const std::string& text, const std::string& value_text, const std::string& source) {
  json value = json::parse(value_text, nullptr, false);
  if (!value.is_discarded()) return value;
  char* end = nullptr;
  const double x = std::strtod(value_text.c_str(), &end);
  if (value_text.empty() || *end != '\0') return value_text;
  if (!std::isfinite(x))
    throw SceneError(source + ": --set \"" + text + "\": " + value_text +
                     " is not a finite number (allowed: magnitudes below about 1.8e308); only a key that takes "
                     "text takes it, quoted as a JSON string: \"" + value_text + "\"");
  return x;
}

// Whether the dotted path (object keys, array indices) names a value in j.
bool has_path(const json& j, const std::string& path) {
  const json* node = &j;
  std::stringstream ss(path);
  std::string part;
  while (std::getline(ss, part, '.')) {
    if (node->is_object() && node->contains(part)) {
      node = &(*node)[part];
    } else if (node->is_array()) {
      char* end = nullptr;
      const long i = std::strtol(part.c_str(), &end, 10);
      if (part.empty() || *end != '\0' || i < 0 || i >= long(node->size())) return false;
      node = &(*node)[std::size_t(i)];
    } else {
      return false;
    }
  }
  return true;
}

}  // namespace

// "a.b.2.c=value": value as override_value() reads it.
void apply_override(json& root, const std::string& text, const std::string& source) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError(source + ": --set \"" + text + "\": expected key=value (for example fluids.0.viscosity=0.01)");
  const std::string path = text.substr(0, eq);
  const json value = override_value(text, text.substr(eq + 1), source);
  json* node = &root;
  std::stringstream ss(path);
  std::string part;
  std::vector<std::string> parts;
  while (std::getline(ss, part, '.')) parts.push_back(part);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& p = parts[i];
    if (p.empty()) throw SceneError(source + ": --set \"" + text + "\": empty key in path");
    const bool last = i + 1 == parts.size();
    if (node->is_array()) {
      char* end = nullptr;
      const long idx = std::strtol(p.c_str(), &end, 10);
      if (*end != '\0' || idx < 0 || idx >= long(node->size()))
        throw SceneError(source + ": --set \"" + text + "\": \"" + p + "\" is not an index of that array (size " +
                         std::to_string(node->size()) + ")");
      node = &(*node)[std::size_t(idx)];
    } else if (node->is_object()) {
      if (!last && !node->contains(p)) (*node)[p] = json::object();
      node = &(*node)[p];
    } else {
      throw SceneError(source + ": --set \"" + text + "\": \"" + p + "\" is inside a value that is not an object");
    }
    if (last) *node = value;
  }
}

// The --set override that wrote the key an error message names (source + ": " + key + ": ..."), if any:
// the key itself or a value inside it, or an object the override created (a misspelt first part of its
// path). A typo or a bad value given on the command line must not be blamed on the scene file.
const std::string* override_of(const std::string& message, const std::string& source,
                               const std::vector<std::string>& overrides, const json& file) {
  if (message.compare(0, source.size() + 2, source + ": ") != 0) return nullptr;
  const std::string rest = message.substr(source.size() + 2);
  const std::string key = rest.substr(0, rest.find(": "));
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it) {  // the last --set of a key wins
    const std::string path = it->substr(0, it->find('='));
    const bool inside = key == path || key.compare(0, path.size() + 1, path + ".") == 0;
    const bool created = path.compare(0, key.size() + 1, key + ".") == 0 && !has_path(file, key);
    if (inside || created) return &*it;
  }
  return nullptr;
}

}  // namespace sph
