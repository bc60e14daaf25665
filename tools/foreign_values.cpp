#include "foreign_values.hpp"

#include <string_view>

namespace achd::cli {
namespace {

using nlohmann::json;

constexpr std::string_view kPrefix("\0achd:", 6);

std::string what(const json& value) {
  const json::binary_t& bytes = value.get_binary();
  return std::string(bytes.begin(), bytes.end());
}

bool foreign(const json& value, std::string_view description) {
  return value.is_binary() && what(value) == description;
}

}  // namespace

void mark_foreign(json& value) {
  if (value.is_string()) {
    const std::string& s = value.get_ref<const std::string&>();
    if (s.compare(0, kPrefix.size(), kPrefix) == 0)
      value = json::binary(json::binary_t::container_type(s.begin() + kPrefix.size(), s.end()));
    return;
  }
  if (value.is_structured())
    for (json& item : value) mark_foreign(item);
}

std::string got(const json& value) { return value.is_binary() ? ", got " + what(value) : ""; }

bool non_finite(const json& value) {
  return foreign(value, "NaN") || foreign(value, "Infinity") || foreign(value, "-Infinity");
}

bool given(const json& object, const char* key) {
  const auto it = object.find(key);
  return it != object.end() && !foreign(*it, "undefined");
}

}  // namespace achd::cli
