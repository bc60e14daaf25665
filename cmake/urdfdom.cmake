# urdfdom: Debian's library for native builds; for Emscripten, wasm/urdfdom.cmake builds
# it from Debian's source packages and defines the same target.
if(EMSCRIPTEN)
  include(${CMAKE_CURRENT_LIST_DIR}/../wasm/urdfdom.cmake)
else()
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(URDFDOM REQUIRED IMPORTED_TARGET urdfdom)
  # TinyXML, urdfdom's parser: the loader reads the rpy attributes with it (urdf.cpp).
  pkg_check_modules(TINYXML REQUIRED IMPORTED_TARGET tinyxml)
  add_library(achd_urdfdom INTERFACE)
  target_link_libraries(achd_urdfdom INTERFACE PkgConfig::URDFDOM PkgConfig::TINYXML)
endif()
