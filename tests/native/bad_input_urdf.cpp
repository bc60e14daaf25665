// Bad URDFs through the C++ API: load_urdf_string and load_urdf_file throw achd::Error
// naming the source, the link or joint and the problem; massless links are valid.
#include <gtest/gtest.h>

#include <fstream>

#include "achd/achd.hpp"
#include "bad_input_urdfs.hpp"

namespace achd::test {
namespace {

std::string error_of(const std::string& xml, const std::string& root, const std::string& tip) {
  try {
    load_urdf_string(xml, root, tip);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BadInputUrdf, EveryKindIsRefusedWithAMessageNamingIt) {
  for (const BadUrdf& b : bad_urdfs()) {
    const std::string msg = error_of(b.xml, b.root, b.tip);
    EXPECT_EQ(msg.rfind("URDF: ", 0), 0u) << b.what << ": " << msg;
    for (const std::string& part : b.message)
      EXPECT_NE(msg.find(part), std::string::npos) << b.what << ": '" << msg << "' lacks '" << part << "'";
  }
}

TEST(BadInputUrdf, MissingFileNamesThePath) {
  try {
    load_urdf_file("/nonexistent/robot.urdf", "a", "b");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/robot.urdf: cannot open file");
  }
}

TEST(BadInputUrdf, FileErrorsStartWithThePath) {
  const std::string path = testing::TempDir() + "bad_input_negative_mass.urdf";
  std::ofstream(path) << robot(link("a") + link("b", unit_inertial("-1")) +
                               joint("j", "revolute", "a", "b"));
  try {
    load_urdf_file(path, "a", "b");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": link 'b': negative mass", 0), 0u) << e.what();
  }
}

// The triangle inequality is checked to 1e-9 relative: a rod (moments 1, 1, 2 within
// 1e-12) and massless links in the middle of a chain are valid.
TEST(BadInputUrdf, BoundaryCasesThatAreValid) {
  EXPECT_NO_THROW(load_urdf_string(robot(link("a") + link("b", unit_inertial("1", "1", "0", "2.000000000001")) +
                                         joint("j", "revolute", "a", "b")),
                                   "a", "b"));
  EXPECT_NO_THROW(load_urdf_string(robot(link("a") + link("b", "") + link("c") +
                                         joint("j1", "revolute", "a", "b") +
                                         "<joint name=\"j2\" type=\"continuous\"><parent link=\"b\"/>"
                                         "<child link=\"c\"/><origin xyz=\"0.2 0 0\"/><axis xyz=\"0 1 0\"/></joint>"),
                                   "a", "c"));
}

}  // namespace
}  // namespace achd::test
