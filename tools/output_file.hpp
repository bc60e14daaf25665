#pragma once
// An output file of the CLI (achd simulate --out, achd accuracy --out) written whole or
// not at all:
//   - a regular file or a new path is written to a temporary file beside it, which
//     commit() closes and renames onto the path (an existing file keeps its mode);
//   - a device, FIFO or socket, any path under /dev/ or /proc/ (e.g. /dev/stdout), and
//     "-" (stdout) are written directly.
// Every write, the close and the rename are checked; a failure is an achd::Error naming
// the path and the system's reason. Destroyed without commit() (a failed or interrupted
// run), the temporary file is removed, so nothing appears under the path.
#include <string>
#include <string_view>

namespace achd::cli {

class OutputFile {
 public:
  explicit OutputFile(const std::string& path);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Buffered; the buffer goes out whenever it passes 1 MiB and at commit().
  void write(std::string_view text);
  // Flushes, closes (syncing a temporary file first) and renames into place.
  void commit();

  const std::string& path() const { return path_; }
  // True when the path itself is written as the run goes (device, FIFO, stdout).
  bool direct() const { return temp_.empty(); }

 private:
  void flush();
  [[noreturn]] void fail(const std::string& what) const;  // errno's reason appended

  std::string path_;    // as the user gave it (messages)
  std::string target_;  // what commit() renames onto (symlinks resolved)
  std::string temp_;    // the temporary file; empty when written directly
  std::string buffer_;
  int fd_ = -1;
  bool owns_fd_ = true;  // false for "-" (stdout stays open)
  bool committed_ = false;
};

}  // namespace achd::cli
