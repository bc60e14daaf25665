#pragma once
// A small command-line parser: positional arguments and `--name value` / `--flag`
// options; anything unknown or missing is an achd::Error naming the option.
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "achd/achd.hpp"

namespace achd::cli {

class Args {
 public:
  // `valued`: options that take a value; `flags`: options that do not.
  Args(int argc, char** argv, const std::set<std::string>& valued, const std::set<std::string>& flags);

  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string get(const std::string& name) const;  // throws if absent
  std::string get(const std::string& name, const std::string& fallback) const;
  // Every value of a repeatable option (--lock J=V ...), in the order given; get() reads
  // the last one.
  std::vector<std::string> all(const std::string& name) const;
  double number(const std::string& name, double fallback) const;  // finite, else throws
  // A decimal integer in [min, max] (parsed in 64 bits), else an achd::Error naming the
  // option and the range.
  std::int64_t integer(const std::string& name, std::int64_t fallback, std::int64_t min, std::int64_t max) const;

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
  std::map<std::string, std::vector<std::string>> repeated_;
};

// --convention, --policy, --tolerance, --absolute-tolerance, --damping, --singular-region,
// --max-damping into Options.
Options solver_options(const Args& args);
// The option names solver_options() reads.
extern const std::set<std::string> kSolverValued;
extern const std::set<std::string> kSolverFlags;

}  // namespace achd::cli
