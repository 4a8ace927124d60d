# kerf's modules (core/module_loader.h): the parts that need gmsh, PETSc and
# MPI, or VTK are shared objects in build/modules (installed in lib/kerf),
# loaded on their first use, so that a run never pays for a library it does
# not use; so is the `kerf` program itself, which its launcher loads once the
# thread policy's variables are set (cli/launcher.cpp). Each exports only its
# `kerf_<name>_module` table: the kerf libraries it links are hidden inside it.
set(KERF_MODULE_DIR ${CMAKE_BINARY_DIR}/modules)
set(KERF_INSTALLED_MODULE_DIR ${CMAKE_INSTALL_LIBDIR}/kerf)
# Every program and library of the build finds them through its RUNPATH;
# installed, bin/kerf through $ORIGIN (the Python module sets its own).
list(APPEND CMAKE_BUILD_RPATH ${KERF_MODULE_DIR})
set(CMAKE_INSTALL_RPATH "$ORIGIN/../${KERF_INSTALLED_MODULE_DIR}")
add_custom_target(kerf_modules ALL)

function(kerf_add_module name)
  cmake_parse_arguments(MODULE "" "" "SOURCES;LINK" ${ARGN})
  set(target kerf_${name}_module)
  add_library(${target} MODULE ${MODULE_SOURCES})
  set_target_properties(${target} PROPERTIES OUTPUT_NAME kerf_${name} PREFIX lib
    LIBRARY_OUTPUT_DIRECTORY ${KERF_MODULE_DIR} CXX_VISIBILITY_PRESET hidden VISIBILITY_INLINES_HIDDEN ON)
  target_link_libraries(${target} PRIVATE ${MODULE_LINK})
  target_link_options(${target} PRIVATE -Wl,--exclude-libs,ALL)
  if(NOT KERF_FUZZ)  # clang's sanitizer runtime is the program's, not the module's: its symbols resolve at load
    target_link_options(${target} PRIVATE -Wl,--no-undefined)
  endif()
  add_dependencies(kerf_modules ${target})
  install(TARGETS ${target} LIBRARY DESTINATION ${KERF_INSTALLED_MODULE_DIR})
endfunction()
