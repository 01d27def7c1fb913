# inkline as a CMake package: `cmake --install build --prefix PREFIX` installs the libraries, their
# public headers under include/inkline/, the inkline program, and lib/cmake/inkline/ with
# inklineConfig.cmake, so that another project can write
#
#   find_package(inkline 0.1 REQUIRED)            # or COMPONENTS core export
#   target_link_libraries(app PRIVATE inkline::core inkline::export)
#
# Components are the libraries built here: core always, gl and export unless switched off.
include(CMakePackageConfigHelpers)

set(INKLINE_PACKAGE_COMPONENTS core)
foreach(component gl export)
  if(TARGET inkline_${component})
    list(APPEND INKLINE_PACKAGE_COMPONENTS ${component})
  endif()
endforeach()
# A static library carries its private link libraries to whatever links it: the config then
# finds them too (OpenMesh, CGAL, Embree, libpng, Cairo; gl opens EGL and OSMesa at run time).
# Shared libraries need only the public ones (GLM, Threads).
get_target_property(core_type inkline_core TYPE)
if(core_type STREQUAL "STATIC_LIBRARY")
  set(INKLINE_PACKAGE_STATIC ON)
else()
  set(INKLINE_PACKAGE_STATIC OFF)
endif()
if(NOT DEFINED INKLINE_HAVE_EMBREE OR NOT INKLINE_HAVE_EMBREE)
  set(INKLINE_HAVE_EMBREE OFF)
endif()

set(INKLINE_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/inkline)
install(EXPORT inklineTargets NAMESPACE inkline:: DESTINATION ${INKLINE_PACKAGE_DIR})
configure_package_config_file(cmake/inklineConfig.cmake.in ${PROJECT_BINARY_DIR}/inklineConfig.cmake
                              INSTALL_DESTINATION ${INKLINE_PACKAGE_DIR})
# 0.x: a new minor version may change the API, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/inklineConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/inklineConfig.cmake ${PROJECT_BINARY_DIR}/inklineConfigVersion.cmake
        DESTINATION ${INKLINE_PACKAGE_DIR})
