#include "args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "achd/names.hpp"

namespace achd::cli {

const std::set<std::string> kSolverValued = {"--convention", "--policy",          "--tolerance",
                                             "--damping",    "--singular-region", "--max-damping"};
const std::set<std::string> kSolverFlags = {"--absolute-tolerance"};

Args::Args(int argc, char** argv, const std::set<std::string>& valued,
           const std::set<std::string>& flags) {
  for (int i = 0; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.size() > 2 && a.compare(0, 2, "--") == 0) {
      if (flags.count(a)) {
        values_[a] = "1";
      } else if (valued.count(a)) {
        if (i + 1 >= argc) throw Error("option " + a + " needs a value");
        values_[a] = argv[++i];
        repeated_[a].push_back(values_[a]);
      } else {
        throw Error("unknown option " + a);
      }
    } else {
      positional_.push_back(a);
    }
  }
}

std::string Args::get(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) throw Error("missing option " + name);
  return it->second;
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
  return has(name) ? get(name) : fallback;
}

std::vector<std::string> Args::all(const std::string& name) const {
  const auto it = repeated_.find(name);
  return it == repeated_.end() ? std::vector<std::string>() : it->second;
}

double Args::number(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  const std::string s = get(name);
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(x))
    throw Error("option " + name + ": '" + s + "' is not a finite number");
  return x;
}

std::int64_t Args::integer(const std::string& name, std::int64_t fallback, std::int64_t min,
                           std::int64_t max) const {
  if (!has(name)) return fallback;
  const std::string s = get(name);
  // Digits with an optional sign, nothing else (strtoll alone would skip blanks).
  const std::size_t sign = !s.empty() && (s[0] == '+' || s[0] == '-') ? 1 : 0;
  const bool well_formed = s.size() > sign && s.find_first_not_of("0123456789", sign) == std::string::npos;
  errno = 0;
  char* end = nullptr;
  const long long x = well_formed ? std::strtoll(s.c_str(), &end, 10) : 0;
  if (!well_formed || errno == ERANGE || x < min || x > max)
    throw Error("option " + name + ": '" + s + "' is not an integer in [" + std::to_string(min) + ", " +
                std::to_string(max) + "]");
  return x;
}

namespace {

// The enum named by `option`'s value among `names` (achd/names.hpp: index = enum value),
// `fallback` when the option is absent.
template <typename Enum, std::size_t N>
Enum named_choice(const Args& args, const std::string& option, const char* const (&names)[N], Enum fallback) {
  const std::string s = args.get(option, names[static_cast<int>(fallback)]);
  for (std::size_t k = 0; k < N; ++k)
    if (s == names[k]) return static_cast<Enum>(k);
  std::string expected;
  for (std::size_t k = 0; k < N; ++k) expected += (k ? " or '" : "'") + std::string(names[k]) + "'";
  throw Error("option " + option + ": expected " + expected + ", got '" + s + "'");
}

}  // namespace

Options solver_options(const Args& args) {
  Options o;
  o.convention = named_choice(args, "--convention", kConventionNames, o.convention);
  o.policy = named_choice(args, "--policy", kSingularityPolicyNames, o.policy);
  o.tolerance = args.number("--tolerance", o.tolerance);
  o.damping = args.number("--damping", o.damping);
  if (o.tolerance < 0) throw Error("option --tolerance must be >= 0");
  if (o.damping < 0) throw Error("option --damping must be >= 0");
  o.singular_region = args.number("--singular-region", o.singular_region);
  o.max_damping = args.number("--max-damping", o.max_damping);
  if (!(o.singular_region > 0)) throw Error("option --singular-region must be > 0");
  if (!(o.max_damping > 0)) throw Error("option --max-damping must be > 0");
  o.absolute_tolerance = args.has("--absolute-tolerance");
  return o;
}

}  // namespace achd::cli
