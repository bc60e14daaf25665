#pragma once
// The bad URDFs every front end must refuse (C++ API, CLI), each with the words its
// error message must contain. Links a (root) and b (tip) unless the case says otherwise.
#include <string>
#include <vector>

namespace achd::test {

struct BadUrdf {
  std::string what;    // test label
  std::string xml;
  std::string root = "a", tip = "b";
  std::vector<std::string> message;  // substrings of the error
};

inline std::string unit_inertial(const std::string& mass = "1", const std::string& ixx = "1",
                                 const std::string& ixy = "0", const std::string& izz = "1") {
  return "<inertial><mass value=\"" + mass + "\"/><inertia ixx=\"" + ixx + "\" ixy=\"" + ixy +
         "\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"" + izz + "\"/></inertial>";
}
inline std::string link(const std::string& name, const std::string& body = unit_inertial()) {
  return "<link name=\"" + name + "\">" + body + "</link>";
}
inline std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                         const std::string& child,
                         const std::string& extra = "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" "
                                                    "upper=\"1\" effort=\"1\" velocity=\"1\"/>") {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/><origin xyz=\"0.1 0 0\"/>" + extra + "</joint>";
}
inline std::string robot(const std::string& body) { return "<robot name=\"r\">" + body + "</robot>"; }
// `depth` elements nested inside one another ("<x><x>...</x></x>").
inline std::string nested(int depth) {
  std::string open, close;
  for (int i = 0; i < depth; ++i) open += "<x>", close += "</x>";
  return open + close;
}

inline std::vector<BadUrdf> bad_urdfs() {
  const std::string ab = link("a") + link("b");
  return {
      {"malformed XML", "<robot name=\"r\"><link name=\"a\">", "a", "b", {"cannot parse URDF"}},
      {"empty document", "", "a", "b", {"cannot parse URDF", "empty"}},
      {"cycle", robot(link("a") + link("b") + link("c") + joint("j1", "revolute", "a", "b") +
                      joint("j2", "revolute", "b", "c") + joint("j3", "revolute", "c", "a")),
       "a", "b", {"cannot parse URDF", "root"}},
      // a cycle that urdfdom accepts because another link (r) is the root
      {"cycle below the root", robot(link("r") + link("a") + link("b") + link("c") +
                                     joint("j0", "revolute", "r", "a") + joint("j1", "revolute", "c", "b") +
                                     joint("j2", "revolute", "b", "c")),
       "r", "b", {"the links form a cycle through link"}},
      {"several roots", robot(ab + link("c") + link("d") + joint("j1", "revolute", "a", "b") +
                              joint("j2", "revolute", "c", "d")),
       "a", "b", {"Two root links", "[a]", "[c]"}},
      {"unknown root", robot(ab + joint("j", "revolute", "a", "b")), "x", "b",
       {"unknown root link 'x'"}},
      {"unknown tip", robot(ab + joint("j", "revolute", "a", "b")), "a", "x",
       {"unknown tip link 'x'"}},
      {"tip not below root", robot(ab + link("c") + joint("j1", "revolute", "a", "b") +
                                   joint("j2", "revolute", "a", "c")),
       "b", "c", {"tip link 'c' is not below root link 'b'"}},
      {"negative mass", robot(link("a") + link("b", unit_inertial("-1")) + joint("j", "revolute", "a", "b")),
       "a", "b", {"link 'b'", "negative mass"}},
      {"inertia not PSD", robot(link("a") + link("b", unit_inertial("1", "1", "2")) +
                                joint("j", "revolute", "a", "b")),
       "a", "b", {"link 'b'", "not positive semi-definite"}},
      {"NaN mass", robot(link("a") + link("b", unit_inertial("nan")) + joint("j", "revolute", "a", "b")),
       "a", "b", {"mass", "nan"}},
      {"Inf inertia", robot(link("a") + link("b", unit_inertial("1", "inf")) + joint("j", "revolute", "a", "b")),
       "a", "b", {"ixx"}},
      {"NaN origin", robot(ab + "<joint name=\"j\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>"
                                "<origin xyz=\"nan 0 0\"/><axis xyz=\"0 0 1\"/></joint>"),
       "a", "b", {"nan"}},
      {"a point mass on the joint axis",
       robot(link("a") + link("b", "<inertial><origin xyz=\"0 0 0.5\"/><mass value=\"1\"/><inertia ixx=\"0\" "
                                   "ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"/></inertial>") +
             joint("j", "revolute", "a", "b")),
       "a", "b", {"joint 'j' moves nothing", "D = S^T IA S = 0"}},
      {"a later coaxial joint frees the motion",
       robot(link("a") + link("b", "") + link("c") + joint("j1", "revolute", "a", "b") +
             "<joint name=\"j2\" type=\"continuous\"><parent link=\"b\"/><child link=\"c\"/><axis xyz=\"0 0 1\"/></joint>"),
       "a", "c", {"joint 'j1' moves nothing"}},
      {"floating joint", robot(ab + joint("j", "floating", "a", "b", "")), "a", "b",
       {"joint 'j'", "unsupported joint type 'floating'"}},
      {"planar joint", robot(ab + joint("j", "planar", "a", "b", "<axis xyz=\"0 0 1\"/>")), "a", "b",
       {"joint 'j'", "unsupported joint type 'planar'"}},
      {"zero axis", robot(ab + joint("j", "revolute", "a", "b",
                                     "<axis xyz=\"0 0 0\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>")),
       "a", "b", {"joint 'j'", "axis is zero"}},
      {"no movable joint", robot(ab + joint("j", "fixed", "a", "b", "")), "a", "b", {"no movable joint"}},
      // <robot> is level 1: 100 more levels inside it make 101
      {"elements nested too deep", robot(ab + joint("j", "revolute", "a", "b") + nested(100)), "a", "b",
       {"cannot parse URDF: elements nested more than 100 deep (line 1)"}},
      {"elements nested 50000 deep", robot(ab + joint("j", "revolute", "a", "b") + nested(50000)), "a", "b",
       {"cannot parse URDF: elements nested more than 100 deep"}},
      // a later joint on the same line, further along it and turned about it, with a
      // massless link between
      {"a later coaxial joint, moved along and turned about the axis",
       robot(link("a") + link("b", "") + link("c") + joint("j1", "revolute", "a", "b") +
             "<joint name=\"j2\" type=\"continuous\"><parent link=\"b\"/><child link=\"c\"/>"
             "<origin xyz=\"0 0 0.3\" rpy=\"0 0 0.7\"/><axis xyz=\"0 0 1\"/></joint>"),
       "a", "c", {"joint 'j1' moves nothing"}},
      // parallel axes at x = 0.1, 0.2, 0.3 with massless links between: j2 and j3 keep d
      // still while j1 turns (the zero configuration is a degenerate four-bar)
      {"three parallel joints on one line with massless links between",
       robot(link("a") + link("b", "") + link("c", "") + link("d") + joint("j1", "revolute", "a", "b") +
             joint("j2", "revolute", "b", "c") + joint("j3", "revolute", "c", "d")),
       "a", "d", {"joint 'j1' moves nothing"}},
      {"joints 1e200 m apart", robot(ab + link("c") + joint("j1", "revolute", "a", "b") +
                                    "<joint name=\"j2\" type=\"continuous\"><parent link=\"b\"/><child link=\"c\"/>"
                                    "<origin xyz=\"1e200 0 0\"/><axis xyz=\"0 0 1\"/></joint>"),
       "a", "c", {"joint 'j2': origin overflows", "inertia", "moved to joint 'j1'"}},
      {"positions that add up past the largest double",
       robot(link("a") + link("b") + link("c") +
             "<joint name=\"j1\" type=\"continuous\"><parent link=\"a\"/><child link=\"b\"/>"
             "<origin xyz=\"1e308 0 0\"/><axis xyz=\"0 0 1\"/></joint>"
             "<joint name=\"j2\" type=\"continuous\"><parent link=\"b\"/><child link=\"c\"/>"
             "<origin xyz=\"1e308 0 0\"/><axis xyz=\"0 0 1\"/></joint>"),
       "a", "c", {"joint 'j2': origin overflows", "position from the root"}},
      {"a link fixed 1e200 m away", robot(ab + link("c") + joint("j", "revolute", "a", "b") +
                                         "<joint name=\"f\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/>"
                                         "<origin xyz=\"1e200 0 0\"/></joint>"),
       "a", "c", {"joint 'f': origin overflows", "link 'c'", "joint 'j'"}},
      {"fixed origins that add up past the largest double",
       robot(ab + link("c", "") + link("d", "") + joint("j", "revolute", "a", "b") +
             "<joint name=\"f1\" type=\"fixed\"><parent link=\"b\"/><child link=\"c\"/><origin xyz=\"1e308 0 0\"/></joint>"
             "<joint name=\"f2\" type=\"fixed\"><parent link=\"c\"/><child link=\"d\"/><origin xyz=\"1e308 0 0\"/></joint>"),
       "a", "d", {"joint 'f2': origin overflows: its position from joint 'j' is not finite"}},
      {"an inertial origin 1e200 m away",
       robot(link("a") + link("b", "<inertial><origin xyz=\"0 1e200 0\"/><mass value=\"1\"/><inertia ixx=\"1\" "
                                   "ixy=\"0\" ixz=\"0\" iyy=\"1\" iyz=\"0\" izz=\"1\"/></inertial>") +
             joint("j", "revolute", "a", "b")),
       "a", "b", {"link 'b': <inertial> overflows"}},
  };
}

}  // namespace achd::test
