#pragma once
// Reading the CLI's JSON input files (cases, scenes) whole, within the size the CLI takes.
#include <string>

namespace achd::cli {

// Reads a case or scene file whole: a regular file of at most 16 MiB
// (kMaxJsonFileBytes), or stdin for "-" when `allow_stdin` (`--case -`). Throws
// achd::Error starting "PATH: " otherwise (read_text_file.hpp); `what` names the file's
// kind in the size message ("a case file").
std::string read_json_file(const std::string& path, const std::string& what, bool allow_stdin = false);

}  // namespace achd::cli
