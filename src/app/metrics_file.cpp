#include "metrics_file.h"

#include <cerrno>
#include <cstring>

namespace sph {

namespace {
constexpr std::chrono::seconds kFlushInterval{1};
}

MetricsFile::MetricsFile(std::string path, const std::string& header) : path_(std::move(path)) {
  file_ = std::fopen(path_.c_str(), "w");
  if (!file_) fail("cannot create", errno);
  write_row(header);
  flush();
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
