# KDL, the optional parity and speed reference: Debian's liborocos-kdl-dev and
# libkdl-parser-dev. Defines ACHD_HAVE_KDL and, when found, the target PkgConfig::KDL.
# Debian's kdl_parser.pc requires ROS's urdf.pc, which requires pluginlib.pc (not
# packaged), so pkg-config fails for it; kdl_parser itself only needs orocos-kdl,
# urdfdom's headers and TinyXML, found here one by one.
pkg_check_modules(KDL QUIET IMPORTED_TARGET orocos-kdl kdl_parser)
if(NOT KDL_FOUND)
  pkg_check_modules(OROCOS_KDL QUIET IMPORTED_TARGET orocos-kdl)
  find_library(KDL_PARSER_LIBRARY kdl_parser)
  find_path(KDL_PARSER_INCLUDE_DIR kdl_parser/kdl_parser.hpp)
  if(OROCOS_KDL_FOUND AND KDL_PARSER_LIBRARY AND KDL_PARSER_INCLUDE_DIR)
    add_library(PkgConfig::KDL INTERFACE IMPORTED)
    target_include_directories(PkgConfig::KDL INTERFACE ${KDL_PARSER_INCLUDE_DIR})
    target_link_libraries(PkgConfig::KDL INTERFACE ${KDL_PARSER_LIBRARY} PkgConfig::OROCOS_KDL
                          PkgConfig::URDFDOM)
    set(KDL_FOUND TRUE)
  endif()
endif()
set(ACHD_HAVE_KDL ${KDL_FOUND})
