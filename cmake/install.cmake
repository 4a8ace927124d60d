# `cmake --install` (and `make install`): the `kerf` command, the libraries,
# the public headers (cmake/public_headers.cmake), the example scenes and study scripts, and a CMake
# package, so that another project's `find_package(kerf)` gets namespaced
# targets (kerf::cli, kerf::app, kerf::problem, ...) that carry their own
# dependencies. CPack turns the same install into a .deb (`make deb`).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(kerf_exported_libraries
  kerf_core kerf_problem kerf_geometry kerf_discretization kerf_solvers kerf_output kerf_app kerf_studies kerf_cli
  kerf_petsc kerf_cholmod kerf_gmsh)
foreach(library ${kerf_exported_libraries})
  string(REPLACE "kerf_" "" short_name ${library})
  set_target_properties(${library} PROPERTIES EXPORT_NAME ${short_name})
endforeach()

set(kerf_header_dir ${CMAKE_INSTALL_INCLUDEDIR}/kerf)
install(TARGETS kerf-view RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS kerf ${kerf_exported_libraries} EXPORT kerfTargets
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT kerfTargets NAMESPACE kerf:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/kerf)

# The public headers and what they include (cmake/public_headers.cmake) keep
# the tree's layout ("problem/material.h"), under include/kerf.
include(${CMAKE_CURRENT_LIST_DIR}/public_headers.cmake)
foreach(header IN LISTS kerf_installed_headers)
  get_filename_component(folder ${header} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/${header} DESTINATION ${kerf_header_dir}/${folder})
endforeach()
install(FILES ${CMAKE_BINARY_DIR}/generated/kerf/version.h DESTINATION ${kerf_header_dir}/kerf)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/kerf/scenes
  FILES_MATCHING PATTERN "*.yaml" PATTERN "*.msh" PATTERN "*.geo")
install(DIRECTORY ${PROJECT_SOURCE_DIR}/studies/plots/ DESTINATION ${CMAKE_INSTALL_DATADIR}/kerf/studies/plots
  FILES_MATCHING PATTERN "*.py")

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/kerfConfig.cmake.in
  ${CMAKE_BINARY_DIR}/kerfConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/kerf)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/kerfConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/kerfConfig.cmake ${CMAKE_BINARY_DIR}/kerfConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/kerf)

# The .deb: Debian's packages kerf links and runs with (the -dev ones too: an
# installed kerf is also a library to build against).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME kerf)
set(CPACK_PACKAGE_CONTACT "kerf developers <kerf@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Soft-tissue cutting: tetrahedral FEM against enriched meshless methods")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
  "libeigen3-dev, libsuitesparse-dev, libopenblas0-openmp, petsc-dev, mpi-default-dev, mpi-default-bin, \
libcgal-dev, libgmsh-dev, gmsh, libvtk9-dev, libyaml-cpp-dev, nlohmann-json3-dev, libnanoflann-dev, \
python3-numpy, python3-matplotlib, cmake, g++")
include(CPack)
