#include "output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "achd/error.hpp"

namespace achd::cli {
namespace {

constexpr std::size_t kFlushBytes = 1 << 20;

bool under_dev_or_proc(const std::string& path) {
  return path.rfind("/dev/", 0) == 0 || path.rfind("/proc/", 0) == 0;
}

}  // namespace

OutputFile::OutputFile(const std::string& path) : path_(path), target_(path) {
  namespace fs = std::filesystem;
  if (path.empty()) throw Error("--out: the path is empty");
  if (path == "-") {
    fd_ = STDOUT_FILENO;
    owns_fd_ = false;
    return;
  }
  struct stat st {};
  const bool exists = ::stat(path.c_str(), &st) == 0;
  if (exists && S_ISDIR(st.st_mode)) throw Error(path + ": is a directory, expected a file");
  std::error_code ec;
  if (exists) {
    const fs::path real = fs::canonical(path, ec);
    if (!ec) target_ = real.string();
  }
  if ((exists && !S_ISREG(st.st_mode)) || under_dev_or_proc(path) || under_dev_or_proc(target_)) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) fail("cannot open for writing");
    return;
  }
  // A temporary file in the target's directory, so that the rename stays on one file
  // system; O_EXCL never takes over someone else's file.
  const fs::path target(target_);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  for (int attempt = 0; fd_ < 0; ++attempt) {
    temp_ = (dir / ("." + target.filename().string() + ".achd-" + std::to_string(::getpid()) + "-" +
                    std::to_string(attempt) + ".tmp"))
                .string();
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0 && (errno != EEXIST || attempt >= 100)) {
      temp_.clear();
      fail("cannot create a file in " + dir.string());
    }
  }
  if (exists) ::fchmod(fd_, st.st_mode & 07777);  // best effort: the file's own mode
}

OutputFile::~OutputFile() {
  if (committed_) return;
  if (fd_ >= 0 && owns_fd_) ::close(fd_);
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

void OutputFile::fail(const std::string& what) const {
  const int e = errno;
  throw Error(path_ + ": " + what + ": " + std::strerror(e));
}

void OutputFile::write(std::string_view text) {
  buffer_.append(text);
  if (buffer_.size() >= kFlushBytes) flush();
}

void OutputFile::flush() {
  const char* p = buffer_.data();
  std::size_t left = buffer_.size();
  while (left > 0) {
    const ssize_t n = ::write(fd_, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("cannot write");
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  buffer_.clear();
}

void OutputFile::commit() {
  flush();
  if (!temp_.empty() && ::fsync(fd_) != 0) fail("cannot write (sync)");
  if (owns_fd_) {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail("cannot write (close)");
  }
  if (!temp_.empty() && std::rename(temp_.c_str(), target_.c_str()) != 0) fail("cannot rename the finished file into place");
  committed_ = true;
}

}  // namespace achd::cli
