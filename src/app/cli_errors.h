// Command-line parse errors in the same form as every other error of the programs: "error: ..." on stderr,
// then where to find help (CLI11's own form has no prefix).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace sph {

inline void use_error_prefix(CLI::App& app) {
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "error: " + std::string(e.what()) + "\nRun with --help for more information.\n";
  });
}

}  // namespace sph
