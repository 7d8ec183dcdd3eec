# Steps of the find_package consumer check, run as `cmake -DKRUG_SETTINGS=<file> -DKRUG_STEP=<step>
# -P package_test.cmake` by the tests in register.cmake. Steps:
#   install   bring the installed targets up to date, then install the build tree into KRUG_PREFIX
#   consumer  configure tests/find_package with CMAKE_PREFIX_PATH=KRUG_PREFIX, build it, run it
#   config    check the installed package files name no dependency the library does not need
#   staged    install with DESTDIR=KRUG_STAGE and a system-like prefix; every file must land under
#             KRUG_STAGE/<prefix>, the app's plotting script among them
cmake_minimum_required(VERSION 3.22)
include(${KRUG_SETTINGS})

function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result}): ${ARGN}")
  endif()
endfunction()

if(KRUG_STEP STREQUAL "install")
  # A no-op when the tree is built; otherwise builds exactly what the install copies.
  run_step("building the installed targets" ${CMAKE_COMMAND} --build ${KRUG_BINARY_DIR}
           --config ${KRUG_BUILD_TYPE} --target ${KRUG_INSTALLED_TARGETS})
  file(REMOVE_RECURSE ${KRUG_PREFIX})
  run_step("cmake --install" ${CMAKE_COMMAND} --install ${KRUG_BINARY_DIR} --prefix ${KRUG_PREFIX}
           --config ${KRUG_BUILD_TYPE})
  file(GLOB_RECURSE config_files ${KRUG_PREFIX}/*/KrugConfig.cmake)
  if(NOT config_files)
    message(FATAL_ERROR "no KrugConfig.cmake under ${KRUG_PREFIX}")
  endif()

elseif(KRUG_STEP STREQUAL "staged")
  set(prefix /opt/krug-staged)
  file(REMOVE_RECURSE ${KRUG_STAGE})
  set(ENV{DESTDIR} ${KRUG_STAGE})
  run_step("cmake --install with DESTDIR" ${CMAKE_COMMAND} --install ${KRUG_BINARY_DIR} --prefix ${prefix}
           --config ${KRUG_BUILD_TYPE})
  file(GLOB_RECURSE staged LIST_DIRECTORIES false RELATIVE ${KRUG_STAGE} ${KRUG_STAGE}/*)
  if(NOT staged)
    message(FATAL_ERROR "nothing was installed under ${KRUG_STAGE}")
  endif()
  foreach(file IN LISTS staged)
    if(NOT file MATCHES "^opt/krug-staged/")
      message(FATAL_ERROR "installed outside the prefix ${prefix}: /${file}")
    endif()
  endforeach()
  if(EXISTS ${KRUG_STAGE}${prefix}/bin/krug AND NOT EXISTS ${KRUG_STAGE}${prefix}/share/krug/plot_history.py)
    message(FATAL_ERROR "the app's plot_history.py is not under ${prefix}/share/krug")
  endif()
  list(LENGTH staged count)
  message(STATUS "${count} files, all under ${prefix}")

elseif(KRUG_STEP STREQUAL "consumer")
  file(REMOVE_RECURSE ${KRUG_CONSUMER_BUILD})
  # The installed Krug first, then wherever this build found Krug's own dependencies. An initial
  # cache file carries the list without shell or argument splitting.
  set(prefix_path ${KRUG_PREFIX} ${KRUG_DEPENDENCY_PREFIX_PATH})
  set(initial_cache ${KRUG_CONSUMER_BUILD}-initial-cache.cmake)
  file(WRITE ${initial_cache} "set(CMAKE_PREFIX_PATH [==[${prefix_path}]==] CACHE STRING \"\")\n")
  run_step("configuring the consumer" ${CMAKE_COMMAND} -C ${initial_cache} -S ${KRUG_CONSUMER_SOURCE}
           -B ${KRUG_CONSUMER_BUILD} -G ${KRUG_GENERATOR} -DCMAKE_BUILD_TYPE=${KRUG_BUILD_TYPE}
           -DCMAKE_CXX_COMPILER=${KRUG_CXX_COMPILER})
  run_step("building the consumer" ${CMAKE_COMMAND} --build ${KRUG_CONSUMER_BUILD} --config ${KRUG_BUILD_TYPE})
  find_program(consumer NAMES consumer PATHS ${KRUG_CONSUMER_BUILD} ${KRUG_CONSUMER_BUILD}/${KRUG_BUILD_TYPE}
               NO_DEFAULT_PATH REQUIRED)
  run_step("running the consumer" ${consumer})

elseif(KRUG_STEP STREQUAL "config")
  # Cairo and the plotting library serve the app only (docs/theory.md §5): never in the package.
  file(GLOB_RECURSE package_files ${KRUG_PREFIX}/*/cmake/Krug/*.cmake)
  if(NOT package_files)
    message(FATAL_ERROR "no package files under ${KRUG_PREFIX}")
  endif()
  foreach(file IN LISTS package_files)
    file(READ ${file} text)
    string(TOLOWER "${text}" text)
    foreach(forbidden cairo plplot matplot gnuplot mathgl sciplot)
      if(text MATCHES "${forbidden}")
        message(FATAL_ERROR "${file} mentions '${forbidden}', an app-only dependency")
      endif()
    endforeach()
  endforeach()
  message(STATUS "package files checked: ${package_files}")

else()
  message(FATAL_ERROR "unknown KRUG_STEP '${KRUG_STEP}'")
endif()
