#include "loops_json.hpp"

#include <cmath>

#include "foreign_values.hpp"
#include "json_text.hpp"
#include "printable.hpp"

namespace achd::cli {
namespace {

using nlohmann::json;

std::string text(const json& v, const std::string& where) {
  if (!v.is_string()) throw Error(where + " must be a string" + got(v));
  return v.get<std::string>();
}

// {"xyz", "rpy"} (each optional, default zeros) as a pose: R = Rz(yaw) Ry(pitch) Rx(roll).
Transform origin(const json& v, const std::string& where) {
  if (!v.is_object()) throw Error(where + " must be an object {xyz, rpy}" + got(v));
  for (const auto& item : v.items())
    if (item.key() != "xyz" && item.key() != "rpy") throw Error(where + ": unknown field '" + printable(item.key()) + "'");
  Transform X;
  if (given(v, "xyz")) X.p = numbers(v["xyz"], where + ".xyz", 3);
  if (given(v, "rpy")) {
    const Eigen::VectorXd a = numbers(v["rpy"], where + ".rpy", 3);
    X.R = (Eigen::AngleAxisd(a[2], Vector3::UnitZ()) * Eigen::AngleAxisd(a[1], Vector3::UnitY()) *
           Eigen::AngleAxisd(a[0], Vector3::UnitX()))
              .toRotationMatrix();
  }
  return X;
}

LoopJointSpec loop_spec(const json& j, const std::string& where) {
  static const char* known[] = {"name", "link_a", "origin_a", "link_b", "origin_b", "type", "axis", "directions"};
  if (!j.is_object())
    throw Error(where + " must be an object {name, link_a, origin_a, link_b, origin_b, type, axis}" + got(j));
  for (const auto& item : j.items()) {
    bool ok = false;
    for (const char* k : known) ok = ok || item.key() == k;
    if (!ok) throw Error(where + ": unknown field '" + printable(item.key()) + "'");
  }
  for (const char* required : {"name", "link_a", "link_b", "type"})
    if (!given(j, required)) throw Error(where + ": missing required field '" + required + "'");
  LoopJointSpec s;
  s.name = text(j["name"], where + ".name");
  s.link_a = text(j["link_a"], where + ".link_a");
  s.link_b = text(j["link_b"], where + ".link_b");
  s.type = loop_type_from_name(text(j["type"], where + ".type"), where + ".type");
  if (given(j, "origin_a")) s.origin_a = origin(j["origin_a"], where + ".origin_a");
  if (given(j, "origin_b")) s.origin_b = origin(j["origin_b"], where + ".origin_b");
  if (given(j, "axis")) s.axis = numbers(j["axis"], where + ".axis", 3);
  if (given(j, "directions")) {
    const json& d = j["directions"];
    if (!d.is_array()) throw Error(where + ".directions must be an array of direction names" + got(d));
    for (size_t k = 0; k < d.size(); ++k)
      s.directions.push_back(text(d[k], where + ".directions[" + std::to_string(k) + "]"));
  }
  return s;
}

std::string link_name(const Model& m, int link) { return link < 0 ? m.root_name : m.links[link].name; }

}  // namespace

std::vector<LoopJointSpec> loop_specs(const json& loops, const std::string& field) {
  if (!loops.is_array()) throw Error(field + " must be an array of loop joints" + got(loops));
  std::vector<LoopJointSpec> out;
  for (size_t k = 0; k < loops.size(); ++k) out.push_back(loop_spec(loops[k], field + "[" + std::to_string(k) + "]"));
  return out;
}

std::vector<LoopJointSpec> parse_loops(const std::string& text, const std::string& source) {
  try {
    const json j = parse_json_text(text);
    if (!j.is_object()) throw Error("a loops file must be a JSON object {\"loops\": [...]}" + got(j));
    for (const auto& item : j.items())
      if (item.key() != "loops") throw Error("unknown field '" + printable(item.key()) + "'");
    if (!j.contains("loops")) throw Error("missing required field 'loops'");
    return loop_specs(j["loops"], "loops");
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
}

std::string loops_json(const Model& m) {
  std::string s = "[";
  for (const LoopJoint& l : m.loops)
    s += std::string(s.size() > 1 ? ", " : "") + "{\"name\": " + json(l.name).dump() + ", \"type\": \"" +
         loop_type_name(l.type) + "\", \"link_a\": " + json(link_name(m, l.link_a)).dump() +
         ", \"link_b\": " + json(link_name(m, l.link_b)).dump() + ", \"directions\": " + json(loop_direction_names(l.directions)).dump() +
         ", \"dropped\": " + json(loop_direction_names(l.dropped)).dump() + "}";
  return s + "]";
}

}  // namespace achd::cli
