#include "json_text.hpp"

#include <set>
#include <vector>

#include "achd/error.hpp"
#include "printable.hpp"

namespace achd::cli {

nlohmann::json parse_json_text(const std::string& text) {
  using nlohmann::json;
  // One entry per object being read, innermost last: the keys seen so far in it and the
  // key it was found under (empty for the top object and objects in arrays).
  struct Open {
    std::set<std::string> keys;
    std::string under;
  };
  std::vector<Open> open;
  std::string last_key;  // the key just read: the name of an object that starts next
  const json::parser_callback_t check = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        open.push_back({{}, last_key});
        last_key.clear();
        break;
      case json::parse_event_t::object_end:
        open.pop_back();
        break;
      case json::parse_event_t::key: {
        const std::string& key = parsed.get_ref<const std::string&>();
        if (!open.back().keys.insert(key).second)
          throw Error("duplicate key '" + printable(key) + "'" +
                      (open.back().under.empty() ? "" : " in '" + printable(open.back().under) + "'"));
        last_key = key;
        break;
      }
      default:  // array_start/end, value: an object inside an array has no key of its own
        last_key.clear();
    }
    return true;
  };
  try {
    return json::parse(text, check);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    throw Error(std::string("invalid JSON: ") + e.what());
  }
}

}  // namespace achd::cli
