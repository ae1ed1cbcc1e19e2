// Back ends by name, chosen at run time: "cpu" (serial reference); later "host" and "cuda".
#pragma once

#include <string>
#include <vector>

#include "../common/backend.h"

namespace sph {

std::vector<std::string> available_backends();
// Throws std::invalid_argument naming the available back ends when `name` is unknown or not built here.
BackendFactory backend_factory(const std::string& name);

}  // namespace sph
