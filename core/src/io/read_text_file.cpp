#include "read_text_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "achd/error.hpp"

namespace achd {
namespace {

// Closes the descriptor on every way out.
struct Fd {
  int fd;
  bool owned;
  ~Fd() {
    if (owned && fd >= 0) ::close(fd);
  }
};

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

}  // namespace

std::string byte_count(std::size_t bytes) {
  if (bytes % (std::size_t{1} << 20) == 0) return std::to_string(bytes >> 20) + " MiB";
  return std::to_string(bytes) + " bytes";
}

std::string read_text_file(const std::string& path, std::size_t limit, const std::string& what,
                           bool allow_stdin) {
  const bool from_stdin = allow_stdin && path == "-";
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer, before
  // fstat could tell it is one. A regular file ignores the flag.
  Fd in{from_stdin ? STDIN_FILENO : ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY), !from_stdin};
  if (in.fd < 0) throw Error(path + ": cannot open file");
  if (!from_stdin) {
    struct stat st {};
    if (::fstat(in.fd, &st) != 0) throw Error(path + ": cannot open file");
    if (!S_ISREG(st.st_mode))
      throw Error(path + ": " + kind_of(st.st_mode) + ", expected a regular file (" + what + ")");
    if (static_cast<unsigned long long>(st.st_size) > limit)
      throw Error(path + ": larger than the " + byte_count(limit) + " limit of " + what);
  }
  // Read to the end, never more than limit + 1 bytes: a file that grows while it is read
  // (or stdin) is caught by the same limit.
  std::string text;
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(in.fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int e = errno;
      throw Error(path + ": cannot read: " + std::strerror(e));
    }
    if (n == 0) break;
    if (text.size() + static_cast<std::size_t>(n) > limit)
      throw Error(path + ": larger than the " + byte_count(limit) + " limit of " + what);
    text.append(buf, static_cast<std::size_t>(n));
  }
  return text;
}

}  // namespace achd
