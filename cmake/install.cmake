# SPDX-License-Identifier: LGPL-3.0-or-later
# The build tree's program finds its assets as an installed one does
# (src/core/assets.hpp): build/share/breastsim/{viewer,app} link to the sources.
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/share/breastsim)
file(CREATE_LINK ${CMAKE_SOURCE_DIR}/src/viewer ${CMAKE_BINARY_DIR}/share/breastsim/viewer SYMBOLIC)
file(CREATE_LINK ${CMAKE_SOURCE_DIR}/src/app/web ${CMAKE_BINARY_DIR}/share/breastsim/app SYMBOLIC)

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)
set(BREASTSIM_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/breastsim)

# The program and its assets: the picture scripts and the 3D page (with the
# two three.js files it loads), the planning app's page.
install(TARGETS breastsim RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY src/viewer/ DESTINATION ${CMAKE_INSTALL_DATADIR}/breastsim/viewer
        PATTERN node_modules EXCLUDE PATTERN __pycache__ EXCLUDE)
# three.js: the page's classic scripts (page.py), the app's modules (static_files.cpp)
set(THREE ${CMAKE_SOURCE_DIR}/src/viewer/web/node_modules/three)
set(THREE_TO ${CMAKE_INSTALL_DATADIR}/breastsim/viewer/web/node_modules/three)
foreach(file build/three.min.js build/three.module.js examples/js/controls/OrbitControls.js
             examples/jsm/controls/OrbitControls.js LICENSE package.json)
  get_filename_component(dir ${file} DIRECTORY)
  install(FILES ${THREE}/${file} DESTINATION ${THREE_TO}/${dir} OPTIONAL)
endforeach()
install(DIRECTORY src/app/web/ DESTINATION ${CMAKE_INSTALL_DATADIR}/breastsim/app)

# The library: every layer (static), its public headers in include/breastsim.
get_property(BREASTSIM_LAYERS GLOBAL PROPERTY BREASTSIM_LAYERS)
get_property(BREASTSIM_HEADER_DIRS GLOBAL PROPERTY BREASTSIM_HEADER_DIRS)
install(TARGETS ${BREASTSIM_LAYERS} EXPORT breastsimTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/breastsim)
foreach(dir ${BREASTSIM_HEADER_DIRS})
  install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/breastsim
          FILES_MATCHING PATTERN "*.hpp" PATTERN web EXCLUDE)
endforeach()
install(EXPORT breastsimTargets NAMESPACE breastsim:: DESTINATION ${BREASTSIM_CMAKE_DIR})
configure_package_config_file(cmake/breastsimConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/breastsimConfig.cmake
                              INSTALL_DESTINATION ${BREASTSIM_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/breastsimConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/breastsimConfig.cmake ${CMAKE_BINARY_DIR}/breastsimConfigVersion.cmake
        DESTINATION ${BREASTSIM_CMAKE_DIR})
