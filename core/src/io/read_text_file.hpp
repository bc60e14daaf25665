#pragma once
// Reading an input file whole, bounded: the CLI's URDF, case and scene files (and the
// loader's load_urdf_file) go through read_text_file, so that a device (/dev/zero,
// /dev/urandom), a directory or a FIFO named as an input ends at once with an error
// naming the path instead of reading until memory runs out or blocking forever.
#include <cstddef>
#include <string>

namespace achd {

// The largest input files read, in bytes (docs/guide/cli.md, "Input files"): robot
// descriptions with inline meshes reach a few MB; cases and scenes are a few KB.
constexpr std::size_t kMaxUrdfFileBytes = std::size_t{64} << 20;   // 64 MiB
constexpr std::size_t kMaxJsonFileBytes = std::size_t{16} << 20;   // 16 MiB

// The whole text of the regular file `path`, or of stdin when `path` is "-" and
// `allow_stdin` (a pipe or a redirected file; it may be anything stdin is, since the
// user chose it explicitly, and is read up to the same limit).
// Throws achd::Error starting "PATH: " when the file cannot be opened, is not a regular
// file (a directory, a device, a FIFO, a socket) or holds more than `limit` bytes
// ("PATH: larger than the 64 MiB limit of a URDF file", with `what` = "a URDF file").
std::string read_text_file(const std::string& path, std::size_t limit, const std::string& what,
                           bool allow_stdin = false);

// "64 MiB", "16 MiB", "1000 bytes": a limit as messages print it.
std::string byte_count(std::size_t bytes);

}  // namespace achd
