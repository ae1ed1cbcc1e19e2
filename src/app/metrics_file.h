// The runner's metrics.csv: every write checked, flushed at least once per second of wall time, so that a
// full disk is an error naming the file and a killed run loses at most its last second of rows.
#pragma once

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace sph {

// An output file could not be written (sph_run exit status 4). The message names the file and the
// operating system's reason.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class MetricsFile {
 public:
  // Creates or truncates path and writes header (one line, without its newline) straight through to the
  // operating system, so an unwritable file is found before the run starts. Throws OutputError.
  // keep_until_step >= 0 (a run continued from a frame of that step): when path already holds rows under
  // the same header, those of steps up to keep_until_step are kept (rewritten through a temporary file and
  // a rename, so an interruption never loses them) and new rows follow; later rows, from the run that was
  // interrupted, are dropped. The kept rows must end with a row of exactly that step at keep_until_time
  // [s] (to the 9 digits written); otherwise the file belongs to another run and std::runtime_error is
  // thrown naming it, and it is left as it is.
  MetricsFile(std::string path, const std::string& header, long long keep_until_step = -1,
              double keep_until_time = 0.0);
  ~MetricsFile();  // closes an unclosed file without checking: call close() to learn of errors
  MetricsFile(const MetricsFile&) = delete;
  MetricsFile& operator=(const MetricsFile&) = delete;

  // Appends one row (without its newline); flushes when the last flush is a second of wall time old.
  // Throws OutputError.
  void write_row(const std::string& row);
  // Flushes when the last flush is a second of wall time old (call it once per step, so rows written
  // long ago never wait in the buffer). Throws OutputError.
  void flush_if_due();
  // Flushes and closes; throws OutputError. Idempotent.
  void close();

  const std::string& path() const { return path_; }
  // Whether rows of an earlier run were kept (see the constructor).
  bool continued() const { return continued_; }

 private:
  void flush();
  [[noreturn]] void fail(const char* action, int error_number) const;

  std::string path_;
  std::FILE* file_ = nullptr;
  bool dirty_ = false;
  bool continued_ = false;
  std::chrono::steady_clock::time_point last_flush_;
};

}  // namespace sph
