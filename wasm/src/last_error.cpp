// The message of the last failed call, read by the JS wrapper right after the failure.
#include "c_api.hpp"

namespace achd::wasm {
namespace {
std::string& last_error() {
  static std::string message;
  return message;
}
}  // namespace

void set_last_error(const char* message) { last_error() = message; }

}  // namespace achd::wasm

ACHD_EXPORT const char* achd_last_error() { return achd::wasm::last_error().c_str(); }
