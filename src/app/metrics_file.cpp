#include "metrics_file.h"

#include <cerrno>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

namespace sph {

namespace {
constexpr std::chrono::seconds kFlushInterval{1};
}

namespace {

// The rows of an existing metrics file under `header` whose step (third column) is at most last_step, or
// nothing when the file is missing or has another header.
std::vector<std::string> rows_until_step(const std::string& path, const std::string& header, long long last_step) {
  std::vector<std::string> rows;
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line) || line != header) return rows;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string time, dt, step;
    if (!std::getline(fields, time, ',') || !std::getline(fields, dt, ',') || !std::getline(fields, step, ',')) break;
    char* end = nullptr;
    const long long s = std::strtoll(step.c_str(), &end, 10);
    if (end == step.c_str() || s > last_step) break;
    rows.push_back(line);
  }
  return rows;
}

}  // namespace

MetricsFile::MetricsFile(std::string path, const std::string& header, long long keep_until_step, double keep_until_time)
    : path_(std::move(path)) {
  const std::vector<std::string> kept =
      keep_until_step >= 0 ? rows_until_step(path_, header, keep_until_step) : std::vector<std::string>{};
  if (!kept.empty()) {  // the last kept row must be the frame's step at the frame's time
    const std::string& last = kept.back();
    const std::size_t c1 = last.find(','), c2 = last.find(',', c1 + 1), c3 = last.find(',', c2 + 1);
    const double t = std::strtod(last.c_str(), nullptr);
    const long long step = std::strtoll(last.c_str() + c2 + 1, nullptr, 10);
    if (c3 == std::string::npos || step != keep_until_step ||
        !(std::fabs(t - keep_until_time) <= 1e-8 * std::max(1.0, std::fabs(keep_until_time)))) {
      std::ostringstream os;
      os.precision(9);
      os << path_ << " belongs to another run: its rows up to step " << keep_until_step << " end at step " << step
         << ", t = " << t << " s, where the frame is at t = " << keep_until_time
         << " s; continue into another --out folder, or move the file away";
      throw std::runtime_error(os.str());
    }
  }
  continued_ = !kept.empty();
  const std::string target = path_;
  if (continued_) path_ = target + ".tmp";  // the old rows stay intact until the new file holds them
  file_ = std::fopen(path_.c_str(), "w");
  if (!file_) fail("cannot create", errno);
  write_row(header);
  for (const std::string& row : kept) write_row(row);
  flush();
  if (continued_) {
    if (std::rename(path_.c_str(), target.c_str()) != 0) fail("cannot rename to metrics.csv", errno);
    path_ = target;
  }
}

MetricsFile::~MetricsFile() {
  if (file_) std::fclose(file_);
}

void MetricsFile::write_row(const std::string& row) {
  if (std::fwrite(row.data(), 1, row.size(), file_) != row.size() || std::fputc('\n', file_) == EOF)
    fail("cannot write", errno);
  dirty_ = true;
  flush_if_due();
}

void MetricsFile::flush_if_due() {
  if (dirty_ && std::chrono::steady_clock::now() - last_flush_ >= kFlushInterval) flush();
}

void MetricsFile::flush() {
  if (std::fflush(file_) != 0) fail("cannot write", errno);
  dirty_ = false;
  last_flush_ = std::chrono::steady_clock::now();
}

void MetricsFile::close() {
  if (!file_) return;
  flush();
  std::FILE* f = file_;
  file_ = nullptr;
  if (std::fclose(f) != 0) fail("cannot close", errno);
}

void MetricsFile::fail(const char* action, int error_number) const {
  throw OutputError(std::string(action) + " " + path_ + ": " + std::strerror(error_number));
}

}  // namespace sph
