// Command-line parse errors in the same form as every other error of the programs: "error: ..." on stderr,
// then, for a misspelt option, the nearest option there is, and where to find help (CLI11's own form has
// no prefix and no suggestion).
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sph {

namespace cli_detail {

// Edit distance (insertions, deletions, substitutions) between a and b.
inline std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// "--name" options of app within a third of the name's length (at least 2 edits) of a misspelt one.
inline std::string suggestion(const CLI::App* app) {
  std::string out;
  for (const std::string& arg : app->remaining()) {
    if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) continue;
    const std::string name = arg.substr(2, arg.find('=') == std::string::npos ? std::string::npos : arg.find('=') - 2);
    std::string best;
    std::size_t best_distance = std::max<std::size_t>(2, name.size() / 3) + 1;
    for (const CLI::Option* o : app->get_options())
      for (const std::string& l : o->get_lnames()) {
        const std::size_t d = edit_distance(name, l);
        if (d < best_distance) best_distance = d, best = l;
      }
    if (!best.empty()) out += arg + ": did you mean --" + best + "?\n";
  }
  return out;
}

}  // namespace cli_detail

inline void use_error_prefix(CLI::App& app) {
  app.failure_message([](const CLI::App* a, const CLI::Error& e) {
    return "error: " + std::string(e.what()) + "\n" + cli_detail::suggestion(a) +
           "Run with --help for the options.\n";
  });
}

}  // namespace sph
