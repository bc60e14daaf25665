#include "case_json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "foreign_values.hpp"
#include "json_text.hpp"
#include "printable.hpp"

namespace achd::cli {
namespace {

using nlohmann::json;

std::string at(const std::string& field, size_t i) { return field + "[" + std::to_string(i) + "]"; }

double number(const json& v, const std::string& where) {
  if (non_finite(v)) throw Error(where + " is not finite");
  if (!v.is_number()) throw Error(where + " must be a number" + got(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw Error(where + " is not finite");
  return x;
}

Eigen::VectorXd vector(const json& v, const std::string& field, int n) {
  if (!v.is_array()) throw Error(field + " must be an array of " + std::to_string(n) + " numbers" + got(v));
  if (static_cast<int>(v.size()) != n)
    throw Error(field + ": expected " + std::to_string(n) + " values, got " + std::to_string(v.size()));
  Eigen::VectorXd out(n);
  for (int i = 0; i < n; ++i) out[i] = number(v[i], at(field, i));
  return out;
}

Vector6 spatial(const json& v, const std::string& where) {
  const Eigen::VectorXd x = vector(v, where, 6);
  return x;
}

// x as JSON text that reads back as x: 17 significant digits (%.17g), or with
// Digits::Shortest the fewest that do (nlohmann's Grisu2, what its dump() writes: much
// faster than printf in wasm). A number that is not finite is written as printf does,
// which is not JSON.
void append_number(std::string& out, double x, Digits digits) {
  char buf[64];
  if (digits == Digits::Shortest && std::isfinite(x)) {
    out.append(buf, nlohmann::detail::to_chars(buf, buf + sizeof buf, x));
    return;
  }
  out.append(buf, static_cast<size_t>(std::snprintf(buf, sizeof buf, "%.17g", x)));
}

std::string fmt(double x, Digits digits = Digits::Seventeen) {
  std::string s;
  append_number(s, x, digits);
  return s;
}

template <typename V>
std::string array(const V& v, Digits digits) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i) s += ", ";
    append_number(s, v[i], digits);
  }
  return s + "]";
}

// x with the fewest significant digits that read back as x ("0.05", "0"), as JS prints it.
std::string shortest(double x) {
  char buf[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

}  // namespace

Eigen::VectorXd numbers(const json& v, const std::string& field, int n) { return vector(v, field, n); }

std::string no_joint(const Model& model, const std::string& name) {
  for (const LockedJoint& l : model.locked_joints)
    if (l.name == name)
      return "joint '" + printable(name) + "' is locked at " + shortest(l.value) +
             " (a side joint of the chain; --lock sets its position)";
  if (model.has_tip()) return "no movable joint '" + printable(name) + "' between the root and the tip";
  return "no movable joint '" + printable(name) + "' below the root link '" + model.root_name + "'";
}

std::string no_link(const Model& model, const std::string& name) {
  if (name == model.root_name && model.floating)
    return "'" + printable(name) + "' is the floating root link, which does not take wrenches or constraint blocks yet "
           "(use a link fixed to it)";
  if (name == model.root_name) return "'" + printable(name) + "' is the root link, which is fixed (nothing acts on the model through it)";
  return "no link '" + printable(name) + "'" + (model.has_tip() ? " on the chain" : " below the root link '" + model.root_name + "'");
}

Eigen::VectorXd joint_vector(const json& v, const std::string& field, const Model& model, bool positions) {
  const int n = positions ? model.num_positions() : model.num_rates();
  const int free = model.floating ? (positions ? 7 : 6) : 0;  // the free joint's numbers
  if (!v.is_object()) {
    if (!v.is_array())
      throw Error(field + " must be an array of " + std::to_string(n) + " numbers or an object {joint name: value}" +
                  got(v));
    return vector(v, field, n);
  }
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  if (positions && model.floating) out[6] = 1;  // qw: the identity orientation
  for (const auto& item : v.items()) {
    const int i = model.joint_index(item.key());
    if (i < 0) throw Error(field + ": " + no_joint(model, item.key()));
    const std::string where = field + "['" + printable(item.key()) + "']";
    if (model.floating && i == 0) out.head(free) = vector(item.value(), where + " (the floating base)", free);
    else out[i + (free == 7 ? 1 : 0)] = number(item.value(), where);
  }
  return out;
}

void link_wrenches(const json& f, const Model& model, const std::string& field, std::vector<Vector6>& out) {
  const int nl = model.num_links();
  if (f.is_object()) {
    out.assign(nl, Vector6::Zero());
    for (const auto& item : f.items()) {
      const int l = model.link_index(item.key());
      if (l < 0) throw Error(field + ": " + no_link(model, item.key()));
      out[l] = spatial(item.value(), field + "['" + printable(item.key()) + "']");
    }
    return;
  }
  if (!f.is_array())
    throw Error(field + " must be an array of 6-element wrenches or an object {link name: wrench}" + got(f));
  if (static_cast<int>(f.size()) != nl)
    throw Error(field + ": expected " + std::to_string(nl) + " wrenches (one per link after the root), got " +
                std::to_string(f.size()));
  for (size_t i = 0; i < f.size(); ++i) out.push_back(spatial(f[i], at(field, i)));
}

namespace {

// "w_fext" / "w_ff" of the tip (prefix "") or of a block: one weight per alpha column.
void driver_weights(const json& j, const std::string& prefix, int nc, ConstraintVector& w_fext,
                    ConstraintVector& w_ff) {
  for (auto [name, out] : {std::pair<const char*, ConstraintVector*>{"w_fext", &w_fext}, {"w_ff", &w_ff}}) {
    if (!given(j, name)) continue;
    const json& v = j[name];
    const std::string field = prefix + name;
    if (!v.is_array()) throw Error(field + " must be an array of numbers in [0, 1], one per alpha column" + got(v));
    if (static_cast<int>(v.size()) != nc)
      throw Error(field + ": expected " + std::to_string(nc) + " values (one per alpha column), got " +
                  std::to_string(v.size()));
    out->resize(nc);
    for (int k = 0; k < nc; ++k) (*out)[k] = number(v[k], at(field, k));
  }
}

// A block's "yields": one boolean per alpha column, true where the column gives way to the
// joints' efforts (ConstraintBlock::yields, bit k for column k).
std::uint8_t yielding_columns(const json& j, const std::string& prefix, int nc) {
  if (!given(j, "yields")) return 0;
  const json& v = j["yields"];
  const std::string field = prefix + "yields";
  if (!v.is_array()) throw Error(field + " must be an array of booleans, one per alpha column" + got(v));
  if (static_cast<int>(v.size()) != nc)
    throw Error(field + ": expected " + std::to_string(nc) + " booleans (one per alpha column), got " +
                std::to_string(v.size()));
  std::uint8_t bits = 0;
  for (int k = 0; k < nc; ++k) {
    if (!v[k].is_boolean()) throw Error(at(field, k) + " must be true or false" + got(v[k]));
    if (v[k].get<bool>()) bits |= static_cast<std::uint8_t>(1u << k);
  }
  return bits;
}

// Constraint columns: `alpha` (up to kMaxConstraints 6-element columns) and `beta` (one
// per column; absent = zeros) of the tip (prefix "") or of a block ("constraints[b].").
void columns(const json& j, const std::string& prefix, ConstraintMatrix& alpha, ConstraintVector& beta,
             bool alpha_required = false) {
  if (alpha_required ? j.contains("alpha") : given(j, "alpha")) {
    const json& a = j["alpha"];
    if (!a.is_array()) throw Error(prefix + "alpha must be an array of 6-element columns" + got(a));
    if (a.size() > static_cast<size_t>(kMaxConstraints))
      throw Error(prefix + "alpha: at most " + std::to_string(kMaxConstraints) + " constraints, got " +
                  std::to_string(a.size()));
    alpha.resize(6, static_cast<Eigen::Index>(a.size()));
    for (size_t k = 0; k < a.size(); ++k) alpha.col(k) = spatial(a[k], at(prefix + "alpha", k));
  }
  const int nc = static_cast<int>(alpha.cols());
  if (given(j, "beta")) {
    const json& b = j["beta"];
    if (!b.is_array()) throw Error(prefix + "beta must be an array of numbers" + got(b));
    if (static_cast<int>(b.size()) != nc)
      throw Error(prefix + "beta: expected " + std::to_string(nc) + " values (one per alpha column), got " +
                  std::to_string(b.size()));
    beta.resize(nc);
    for (int k = 0; k < nc; ++k) beta[k] = number(b[k], at(prefix + "beta", k));
  } else {
    beta.setZero(nc);
  }
}

}  // namespace

void constraint_blocks(const json& cs, const Model& model, Case& c) {
  if (!cs.is_array())
    throw Error("constraints must be an array of blocks {link, alpha, beta, point, link_b, point_b}" + got(cs));
  for (size_t b = 0; b < cs.size(); ++b) {
    const json& j = cs[b];
    const std::string where = at("constraints", b);
    if (!j.is_object()) throw Error(where + " must be an object {link, alpha, beta, point, link_b, point_b}" + got(j));
    for (const auto& item : j.items())
      if (item.key() != "link" && item.key() != "alpha" && item.key() != "beta" && item.key() != "point" &&
          item.key() != "w_fext" && item.key() != "w_ff" && item.key() != "link_b" && item.key() != "point_b" &&
          item.key() != "yields")
        throw Error(where + ": unknown field '" + printable(item.key()) + "'");
    if (!j.contains("link")) throw Error(where + ": missing required field 'link'");
    if (!j.contains("alpha")) throw Error(where + ": missing required field 'alpha'");
    if (!j["link"].is_string()) throw Error(where + ".link must be a link name" + got(j["link"]));
    ConstraintBlock block;
    const std::string name = j["link"].get<std::string>();
    block.link = model.link_index(name);
    if (block.link < 0) throw Error(where + ".link: " + no_link(model, name));
    columns(j, where + ".", block.alpha, block.beta, true);
    driver_weights(j, where + ".", static_cast<int>(block.alpha.cols()), block.w_fext, block.w_ff);
    block.yields = yielding_columns(j, where + ".", static_cast<int>(block.alpha.cols()));
    if (given(j, "point")) block.point = vector(j["point"], where + ".point", 3);
    // a relative block: alpha^T (a_A - a_B) = beta, B the link named by link_b
    if (given(j, "link_b")) {
      if (!j["link_b"].is_string()) throw Error(where + ".link_b must be a link name" + got(j["link_b"]));
      const std::string name_b = j["link_b"].get<std::string>();
      block.link_b = model.link_index(name_b);
      if (block.link_b < 0) throw Error(where + ".link_b: " + no_link(model, name_b));
      if (block.link_b == block.link)
        throw Error(where + ".link_b: the block would hold link '" + printable(name) +
                    "' relative to itself; name another link or leave link_b out");
    }
    if (given(j, "point_b")) {
      if (block.link_b < 0) throw Error(where + ".point_b: given without link_b (the second link it is a point of)");
      block.point_b = vector(j["point_b"], where + ".point_b", 3);
    }
    c.constraints.push_back(block);
  }
}

namespace {

// "qdd_given": the prescribed joints' accelerations, as an object keyed by joint name or
// an array in model order with null for a joint that is not prescribed.
void prescribed_joints(const json& v, const Model& model, Case& c) {
  const int nj = model.num_rates();
  c.qdd_given = Eigen::VectorXd::Zero(nj);
  c.prescribed.assign(nj, false);
  if (v.is_object()) {
    for (const auto& item : v.items()) {
      const int i = model.joint_index(item.key());
      if (i < 0) throw Error("qdd_given: " + no_joint(model, item.key()));
      const std::string where = "qdd_given['" + printable(item.key()) + "']";
      if (model.floating && i == 0) {  // the free joint: [dv/dt; dw/dt], all six prescribed
        c.qdd_given.head<6>() = vector(item.value(), where + " (the floating base)", 6);
        for (int k = 0; k < 6; ++k) c.prescribed[k] = true;
        continue;
      }
      c.qdd_given[i] = number(item.value(), where);
      c.prescribed[i] = true;
    }
    return;
  }
  if (!v.is_array())
    throw Error("qdd_given must be an object {joint name: acceleration} or an array of " + std::to_string(nj) +
                " numbers or nulls (null: the joint is not prescribed)" + got(v));
  if (static_cast<int>(v.size()) != nj)
    throw Error("qdd_given: expected " + std::to_string(nj) + " values (one per joint, null where not prescribed), got " +
                std::to_string(v.size()));
  for (int i = 0; i < nj; ++i) {
    if (v[i].is_null()) continue;
    c.qdd_given[i] = number(v[i], at("qdd_given", i) + " (joint '" + model.bodies[i].joint_name + "')");
    c.prescribed[i] = true;
  }
}

// A JSON string. (Names of printable ASCII without quotes or backslashes, nearly all,
// are written as they are: what dump() writes for them, without its cost.)
std::string quoted(const std::string& s) {
  for (const char ch : s)
    if (ch < 0x20 || ch > 0x7e || ch == '"' || ch == '\\') return json(s).dump();
  return '"' + s + '"';
}

}  // namespace

Case case_from_json(const json& j, const Model& model, const std::string& source) {
  try {
    if (!j.is_object()) throw Error("the case must be a JSON object" + got(j));
    static const char* known[] = {"q",          "qd",        "gravity",     "alpha",     "beta", "f_ext",
                                  "ff_torques", "qdd_given", "constraints", "f_virtual", "w_fext", "w_ff",
                                  "loop_beta"};
    for (const auto& item : j.items()) {
      bool ok = false;
      for (const char* k : known) ok = ok || item.key() == k;
      if (!ok) throw Error("unknown field '" + printable(item.key()) + "'");
    }
    if (!j.contains("q")) throw Error("missing required field 'q'");
    if (!j.contains("gravity")) throw Error("missing required field 'gravity'");
    Case c;
    c.q = joint_vector(j["q"], "q", model, true);
    c.gravity = vector(j["gravity"], "gravity", 3);
    if (given(j, "qd")) c.qd = joint_vector(j["qd"], "qd", model);
    if (given(j, "ff_torques")) c.ff_torques = joint_vector(j["ff_torques"], "ff_torques", model);
    columns(j, "", c.alpha, c.beta);
    driver_weights(j, "", static_cast<int>(c.alpha.cols()), c.w_fext, c.w_ff);
    if (given(j, "constraints")) constraint_blocks(j["constraints"], model, c);
    if (given(j, "f_ext")) link_wrenches(j["f_ext"], model, "f_ext", c.f_ext);
    if (given(j, "f_virtual")) link_wrenches(j["f_virtual"], model, "f_virtual", c.f_virtual);
    if (given(j, "qdd_given")) prescribed_joints(j["qdd_given"], model, c);
    if (given(j, "loop_beta")) c.loop_beta = vector(j["loop_beta"], "loop_beta", model.num_loop_columns());
    validate(model, c);
    return c;
  } catch (const Error& e) {
    if (source.empty()) throw;
    throw Error(source + ": " + e.what());
  }
}

Case parse_case(const std::string& text, const Model& model, const std::string& source) {
  json j;
  try {
    j = parse_json_text(text);  // duplicate keys refused
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  return case_from_json(j, model, source);
}

std::string result_json(const Model& model, const Data& d, const Case& c, Digits digits) {
  std::string s = "{\n";
  s += "  \"joints\": [";  // a floating base's free joint once (its six entries in qdd)
  for (int i = 0; i < model.num_rates(); ++i)
    if (!model.floating || i == 0 || i >= 6) s += (i ? ", " : "") + quoted(model.bodies[i].joint_name);
  s += "],\n  \"links\": [" + quoted(model.root_name);
  for (const Link& l : model.links) s += ", " + quoted(l.name);
  s += "],\n";
  s += "  \"qdd\": " + array(d.qdd, digits) + ",\n";
  s += "  \"constraint_torques\": " + array(d.constraint_torques, digits) + ",\n";
  s += "  \"total_torques\": " + array(d.total_torques, digits) + ",\n";
  if (model.couplings.empty() && model.loops.empty()) {
    s += "  \"nu\": " + array(d.nu, digits) + ",\n";
  } else {  // the loops' and coupled joints' forces follow the blocks', each entry named
    Eigen::VectorXd nu(d.nu.size() + d.coupling_forces.size());
    nu << d.nu, d.coupling_forces;
    s += "  \"nu\": " + array(nu, digits) + ",\n  \"nu_owners\": [";
    std::string owners;  // (no constraint columns in nu with the constraints effect off)
    if (d.nu.size())
      for (int k = 0; k < c.alpha.cols(); ++k) owners += std::string(owners.empty() ? "" : ", ") + "\"tip\"";
    if (d.nu.size())
      for (const ConstraintBlock& b : c.constraints)
        for (int k = 0; k < b.alpha.cols(); ++k)
        owners += std::string(owners.empty() ? "" : ", ") + quoted("link " + model.links[b.link].name);
    if (d.nu.size())
      for (const LoopJoint& l : model.loops)
        for (int k = 0; k < l.num_columns(); ++k) owners += std::string(owners.empty() ? "" : ", ") + quoted("loop " + l.name);
    for (const JointCoupling& j : model.couplings)
      owners += std::string(owners.empty() ? "" : ", ") + quoted("coupling " + model.bodies[j.follower].joint_name);
    s += owners + "],\n";
  }
  s += "  \"joint_torques\": " + array(d.joint_torques, digits) + ",\n";
  if (!c.f_virtual.empty()) s += "  \"virtual_torques\": " + array(d.virtual_torques, digits) + ",\n";
  if (c.any_prescribed()) {  // null where the joint is not prescribed, as in qdd_given
    s += "  \"prescribed_torques\": [";
    for (int i = 0; i < model.num_rates(); ++i)
      s += (i ? ", " : "") + (c.prescribed[i] ? fmt(d.prescribed_torques[i], digits) : std::string("null"));
    s += "],\n";
  }
  s += "  \"constraint_wrench\": " + array(d.constraint_wrench, digits) + ",\n";
  s += "  \"constraint_wrenches\": [";  // one per block of c.constraints
  for (size_t b = 0; b < c.constraints.size(); ++b) s += (b ? ", " : "") + array(d.constraint_wrenches[b], digits);
  s += "],\n";
  if (!model.loops.empty()) {  // one per loop joint, after the blocks': alpha nu at Q, what link a exerts
    s += "  \"loop_wrenches\": [";
    for (size_t l = 0; l < model.loops.size(); ++l)
      s += (l ? ", " : "") + array(d.constraint_wrenches[c.constraints.size() + l], digits);
    s += "],\n";
  }
  s += "  \"link_accelerations\": [";
  for (int i = 0; i <= model.num_links(); ++i)
    s += std::string(i ? ",\n    " : "\n    ") + array(d.link_accelerations[i], digits);
  s += "\n  ],\n";
  s += "  \"rank\": " + std::to_string(d.rank) + ",\n";
  s += "  \"sigma_min\": " + fmt(sigma_min(d), digits) + ",\n";
  s += "  \"dropped\": [";
  for (Eigen::Index k = 0; k < d.dropped.cols(); ++k)
    s += (k ? ", " : "") + array(d.dropped.col(k), digits);
  s += "]";
  // Blocks with columns that give way to the efforts: the largest |tau_i| / effort_i of the
  // solve that follows them and how far this solve gave them up (Data::effort_ratio, yielded).
  if (std::any_of(c.constraints.begin(), c.constraints.end(), [](const ConstraintBlock& b) { return b.yields != 0; }))
    s += ",\n  \"effort_ratio\": " + fmt(d.effort_ratio, digits) + ",\n  \"yielded\": " + fmt(d.yielded, digits);
  if (!model.locked_joints.empty()) s += ",\n  \"locked_joints\": " + locked_joints_json(model, digits);
  return s + "\n}\n";
}

std::string locked_joints_json(const Model& model, Digits digits) {
  std::string s = "[";
  for (size_t k = 0; k < model.locked_joints.size(); ++k)
    s += std::string(k ? ", " : "") + "{\"name\": " + quoted(model.locked_joints[k].name) +
         ", \"value\": " + fmt(model.locked_joints[k].value, digits) + "}";
  return s + "]";
}

}  // namespace achd::cli
