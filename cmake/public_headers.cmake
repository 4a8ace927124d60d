# The headers kerf installs: the public ones (what a program built against
# kerf includes: the command line, a material law of its own, a scene read,
# resolved and run, a run's typed record) and every kerf header they include,
# followed to the end. Nothing else is installed: the bodies, solvers and
# kernels behind them are not API and may change without notice.
set(kerf_public_headers
  cli/command_line.h
  core/denormals.h
  core/thread_policy.h
  problem/material.h
  problem/user_material.h
  problem/scene.h
  problem/scene_reader.h
  problem/scene_json.h
  app/run_scene.h
  app/session.h
  app/run_record.h
  app/summary_json.h)

# out: the headers above and those they include (paths relative to the
# source tree), each once; configure runs again when any of them changes.
function(kerf_included_headers out)
  set(pending ${ARGN})
  set(found)
  while(pending)
    list(POP_FRONT pending header)
    if(header IN_LIST found)
      continue()
    endif()
    list(APPEND found ${header})
    set_property(DIRECTORY ${PROJECT_SOURCE_DIR} APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
      ${PROJECT_SOURCE_DIR}/${header})
    file(STRINGS ${PROJECT_SOURCE_DIR}/${header} includes REGEX "^#include \"")
    foreach(line IN LISTS includes)
      string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" included "${line}")
      if(EXISTS ${PROJECT_SOURCE_DIR}/${included})  # kerf/version.h is generated: installed on its own
        list(APPEND pending ${included})
      endif()
    endforeach()
  endwhile()
  list(SORT found)
  set(${out} ${found} PARENT_SCOPE)
endfunction()

kerf_included_headers(kerf_installed_headers ${kerf_public_headers})
