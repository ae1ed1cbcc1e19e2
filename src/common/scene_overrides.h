// The command line's --set key=value overrides of a scene file (scene_loader.cpp applies them).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sph {

// Sets the value at a dotted path "a.b.2.c=value" in root (objects created along the way; an array index must
// exist). The value is JSON, or else a finite number as strtod reads it, or else the text as a string.
// Throws SceneError naming source and the override when the text or the path is malformed.
void apply_override(nlohmann::json& root, const std::string& text, const std::string& source);

// The --set override (an element of overrides) that wrote the key a reader's error message names
// (source + ": " + key + ": ..."): the key itself or a value inside it, or an object the override created in
// file (the scene before the overrides). nullptr when the key came from the file.
const std::string* override_of(const std::string& message, const std::string& source,
                               const std::vector<std::string>& overrides, const nlohmann::json& file);

}  // namespace sph
