#include "json_file.hpp"

#include "read_text_file.hpp"

namespace achd::cli {

std::string read_json_file(const std::string& path, const std::string& what, bool allow_stdin) {
  return read_text_file(path, kMaxJsonFileBytes, what, allow_stdin);
}

}  // namespace achd::cli
