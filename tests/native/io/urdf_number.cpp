// The numbers the wasm build's urdfdom accepts (wasm/urdfdom_shim/urdf_number.hpp) are
// those the native urdfdom accepts: achd::parse_urdf_number against Debian's
// urdf::strToDouble, on hand-picked and random strings, accepted or not and bit for bit.
#include "../../../wasm/urdfdom_shim/urdf_number.hpp"

#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <urdf_model/utils.h>

namespace {

void expect_same(const std::string& s) {
  bool native_ok = true;
  double native = 0;
  try {
    native = urdf::strToDouble(s.c_str());
  } catch (const std::runtime_error&) {
    native_ok = false;
  }
  double ours = 0;
  const bool ours_ok = achd::parse_urdf_number(s.c_str(), ours);
  ASSERT_EQ(ours_ok, native_ok) << "'" << s << "'";
  if (native_ok) ASSERT_EQ(std::memcmp(&ours, &native, sizeof ours), 0) << "'" << s << "': " << ours << " vs " << native;
}

TEST(UrdfNumber, SameAsNativeUrdfdom) {
  for (const char* s : {"1", "-1", "+1", "1.5", ".5", "5.", "-.5e-3", "1e5", "1E+5", "4e-320", "1e-400", "-1e-400",
                        "2.2250738585072011e-308", "1.7976931348623157e308", "1.8e308", "1e400", "-1e400", "nan",
                        "NaN", "inf", "-inf", "infinity", "0x1p3", "0x10", "", " ", "  1", "1 ", "\t1", "1e", "1e+",
                        ".", "-", "+.", ".e1", "1.2.3", "1e5.5", "1,5", "1e+-5", "--1", "00012", "0.0000", "-0",
                        "1d5", "١", "1\n", "\n1", "\v1", "1f"})
    expect_same(s);
  const std::string alphabet = "0123456789.eE+- xXpPnaif\t";
  std::mt19937 rng(5);
  std::uniform_int_distribution<size_t> pick(0, alphabet.size() - 1);
  std::uniform_int_distribution<int> length(0, 12);
  for (int k = 0; k < 200000; ++k) {
    std::string s;
    for (int n = length(rng); n > 0; --n) s += alphabet[pick(rng)];
    expect_same(s);
  }
}

}  // namespace
