#include "case_json.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace achd::cli {
namespace {

using nlohmann::json;

std::string at(const std::string& field, size_t i) { return field + "[" + std::to_string(i) + "]"; }

double number(const json& v, const std::string& where) {
  if (!v.is_number()) throw Error(where + " must be a number");
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw Error(where + " is not finite");
  return x;
}

Eigen::VectorXd vector(const json& v, const std::string& field, int n) {
  if (!v.is_array()) throw Error(field + " must be an array of " + std::to_string(n) + " numbers");
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

std::string fmt(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

template <typename V>
std::string array(const V& v) {
  std::string s = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt(v[i]);
  return s + "]";
}

// "qdd_given": the prescribed joints' accelerations, as an object keyed by joint name or
// an array in model order with null for a joint that is not prescribed.
void prescribed_joints(const json& v, const Model& model, Case& c) {
  const int nj = model.num_joints();
  c.qdd_given = Eigen::VectorXd::Zero(nj);
  c.prescribed.assign(nj, false);
  if (v.is_object()) {
    for (const auto& item : v.items()) {
      const int i = model.joint_index(item.key());
      if (i < 0)
        throw Error("qdd_given: no movable joint '" + item.key() + "' between the root and the tip");
      c.qdd_given[i] = number(item.value(), "qdd_given['" + item.key() + "']");
      c.prescribed[i] = true;
    }
    return;
  }
  if (!v.is_array())
    throw Error("qdd_given must be an object {joint name: acceleration} or an array of " + std::to_string(nj) +
                " numbers or nulls (null: the joint is not prescribed)");
  if (static_cast<int>(v.size()) != nj)
    throw Error("qdd_given: expected " + std::to_string(nj) + " values (one per joint, null where not prescribed), got " +
                std::to_string(v.size()));
  for (int i = 0; i < nj; ++i) {
    if (v[i].is_null()) continue;
    c.qdd_given[i] = number(v[i], at("qdd_given", i) + " (joint '" + model.bodies[i].joint_name + "')");
    c.prescribed[i] = true;
  }
}

}  // namespace

Case case_from_json(const json& j, const Model& model, const std::string& source) {
  try {
    if (!j.is_object()) throw Error("the case must be a JSON object");
    static const char* known[] = {"q", "qd", "gravity", "alpha", "beta", "f_ext", "ff_torques", "qdd_given"};
    for (const auto& item : j.items()) {
      bool ok = false;
      for (const char* k : known) ok = ok || item.key() == k;
      if (!ok) throw Error("unknown field '" + item.key() + "'");
    }
    const int nj = model.num_joints();
    if (!j.contains("q")) throw Error("missing required field 'q'");
    if (!j.contains("gravity")) throw Error("missing required field 'gravity'");
    Case c;
    c.q = vector(j["q"], "q", nj);
    c.gravity = vector(j["gravity"], "gravity", 3);
    if (j.contains("qd")) c.qd = vector(j["qd"], "qd", nj);
    if (j.contains("ff_torques")) c.ff_torques = vector(j["ff_torques"], "ff_torques", nj);
    if (j.contains("alpha")) {
      const json& a = j["alpha"];
      if (!a.is_array()) throw Error("alpha must be an array of 6-element columns");
      if (a.size() > static_cast<size_t>(kMaxConstraints))
        throw Error("alpha: at most " + std::to_string(kMaxConstraints) + " constraints, got " +
                    std::to_string(a.size()));
      c.alpha.resize(6, static_cast<Eigen::Index>(a.size()));
      for (size_t k = 0; k < a.size(); ++k) c.alpha.col(k) = spatial(a[k], at("alpha", k));
    }
    const int nc = c.num_constraints();
    if (j.contains("beta")) {
      const json& b = j["beta"];
      if (!b.is_array()) throw Error("beta must be an array of numbers");
      if (static_cast<int>(b.size()) != nc)
        throw Error("beta: expected " + std::to_string(nc) + " values (one per alpha column), got " +
                    std::to_string(b.size()));
      c.beta.resize(nc);
      for (int k = 0; k < nc; ++k) c.beta[k] = number(b[k], at("beta", k));
    } else {
      c.beta.setZero(nc);
    }
    if (j.contains("f_ext")) {
      const json& f = j["f_ext"];
      if (!f.is_array()) throw Error("f_ext must be an array of 6-element wrenches");
      if (static_cast<int>(f.size()) != model.num_links())
        throw Error("f_ext: expected " + std::to_string(model.num_links()) +
                    " wrenches (one per link after the root), got " + std::to_string(f.size()));
      for (size_t i = 0; i < f.size(); ++i) c.f_ext.push_back(spatial(f[i], at("f_ext", i)));
    }
    if (j.contains("qdd_given")) prescribed_joints(j["qdd_given"], model, c);
    validate(model, c);
    return c;
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
}

Case parse_case(const std::string& text, const Model& model, const std::string& source) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    throw Error(source + ": invalid JSON: " + e.what());
  }
  return case_from_json(j, model, source);
}

std::string result_json(const Model& model, const Data& d, const Case& c) {
  std::string s = "{\n";
  s += "  \"qdd\": " + array(d.qdd) + ",\n";
  s += "  \"constraint_torques\": " + array(d.constraint_torques) + ",\n";
  s += "  \"total_torques\": " + array(d.total_torques) + ",\n";
  s += "  \"nu\": " + array(d.nu) + ",\n";
  s += "  \"joint_torques\": " + array(d.joint_torques) + ",\n";
  if (c.any_prescribed()) {  // null where the joint is not prescribed, as in qdd_given
    s += "  \"prescribed_torques\": [";
    for (int i = 0; i < model.num_joints(); ++i)
      s += (i ? ", " : "") + (c.prescribed[i] ? fmt(d.prescribed_torques[i]) : std::string("null"));
    s += "],\n";
  }
  s += "  \"constraint_wrench\": " + array(d.constraint_wrench) + ",\n";
  s += "  \"link_accelerations\": [";
  for (int i = 0; i <= model.num_links(); ++i)
    s += std::string(i ? ",\n    " : "\n    ") + array(d.link_accelerations[i]);
  s += "\n  ],\n";
  s += "  \"rank\": " + std::to_string(d.rank) + ",\n";
  s += "  \"sigma_min\": " + fmt(sigma_min(d)) + ",\n";
  s += "  \"dropped\": [";
  for (Eigen::Index k = 0; k < d.dropped.cols(); ++k)
    s += (k ? ", " : "") + array(d.dropped.col(k));
  s += "]\n}\n";
  return s;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace achd::cli
