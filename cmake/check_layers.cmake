# The module walls (docs/architecture.md, "Layers"): a file of a module may include the headers of its
# own module and of the modules below it, never of a module above it or beside it. Run at every build
# (target krug_layers, which every library depends on); an upward include stops the build and names
# the file, the line and the two modules.
#
#   cmake -DKRUG_ROOT=<source dir> -P cmake/check_layers.cmake
#
# The order, lowest first, as ranks; modules of one rank (material, fracture, particles; contact,
# boundary) are siblings that must not include one another.
set(order core mesh material fracture particles contact boundary hydro solver setup scenario run output)
set(rank_core 0)
set(rank_mesh 1)
set(rank_material 2)
set(rank_fracture 2)
set(rank_particles 2)
set(rank_contact 3)
set(rank_boundary 3)
set(rank_hydro 4)
set(rank_solver 5)
set(rank_setup 6)
set(rank_scenario 7)
set(rank_run 8)
set(rank_output 9)

set(failures "")
foreach(module IN LISTS order)
  file(GLOB_RECURSE files
       "${KRUG_ROOT}/include/krug/${module}/*.hpp" "${KRUG_ROOT}/src/${module}/*.cpp" "${KRUG_ROOT}/src/${module}/*.hpp")
  foreach(file IN LISTS files)
    file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]krug/[a-z_]+/")
    foreach(line IN LISTS lines)
      string(REGEX MATCH "krug/([a-z_]+)/" _ "${line}")
      set(target "${CMAKE_MATCH_1}")
      if(target STREQUAL module)
        continue()
      endif()
      if(NOT DEFINED rank_${target})
        list(APPEND failures "${file}: includes an unknown module \"${target}\": ${line}")
      elseif(NOT rank_${target} LESS rank_${module})
        list(APPEND failures "${file}: module \"${module}\" includes \"${target}\", which is not below it: ${line}")
      endif()
    endforeach()
  endforeach()
endforeach()

if(failures)
  list(JOIN failures "\n  " text)
  message(FATAL_ERROR "upward include across the module walls (cmake/check_layers.cmake):\n  ${text}")
endif()
