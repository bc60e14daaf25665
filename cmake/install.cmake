# `cmake --install` puts the library, headers and a package config so that C++ users
# can `find_package(achd)` and link `achd::achd`.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
install(TARGETS achd EXPORT achdTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY core/include/achd DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS achd_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT achdTargets NAMESPACE achd:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/achd)
configure_package_config_file(cmake/achdConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/achdConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/achd)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/achdConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/achdConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/achdConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/achd)
