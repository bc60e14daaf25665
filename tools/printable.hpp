#pragma once
// Names from input files (JSON keys, joint and link names) inside error messages: a
// control character would cut the message (a NUL ends what()) or break its one line (a
// newline), so each is written as an escape: \n, \r, \t, \0, other bytes below 0x20 and
// DEL as \xNN. Everything else, UTF-8 included, is kept as it is.
#include <string>
#include <string_view>

namespace achd::cli {

std::string printable(std::string_view text);

}  // namespace achd::cli
