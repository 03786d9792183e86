# verilate_unity(TARGET <verilate() arguments>): verilate() (Verilator's CMake function), then the
# model compiled as two translation units, as Verilator's own makefile does (VM_PARALLEL_BUILDS=0:
# one __ALL.cpp): its fast code (the eval functions: OPT_FAST) in one, the rest (constructors,
# trace set-up, symbol table: OPT_SLOW, or the target's flags) in the other. verilate() compiles
# each of the 10 to 17 files Verilator writes apart, and every compile pays almost a second of start
# (reading the precompiled verilated.h) for often less work: the largest configuration compiles in
# 14 core-s as two units, 22 as 17 files.
# The generated files stay sources of TARGET (so that Verilator runs before they are read), marked
# as headers; the two units include them, written after each Verilator run from that run's lists
# (cmake/verilate_unity_write.cmake: a configure-time list would name an earlier run's files, which
# Verilator leaves behind, until the next configure).
find_package(verilator 5 REQUIRED HINTS /usr/share/verilator $ENV{VERILATOR_ROOT})

function(verilate_unity target)
  cmake_parse_arguments(ARG "COVERAGE;TRACE;TRACE_FST;SYSTEMC;TRACE_STRUCTS"  # verilate()'s keywords
                        "PREFIX;TOP_MODULE;THREADS;TRACE_THREADS;DIRECTORY"
                        "SOURCES;VERILATOR_ARGS;INCLUDE_DIRS;OPT_SLOW;OPT_FAST;OPT_GLOBAL" ${ARGN})
  verilate(${target} ${ARGN})
  get_target_property(binary_dir ${target} BINARY_DIR)
  set(vdir "${binary_dir}/CMakeFiles/${target}.dir/${ARG_PREFIX}.dir")
  if(ARG_DIRECTORY)
    set(vdir "${ARG_DIRECTORY}")
  endif()
  include("${vdir}/${ARG_PREFIX}_copy.cmake")  # the file lists verilate() read
  set(fast ${${ARG_PREFIX}_CLASSES_FAST} ${${ARG_PREFIX}_SUPPORT_FAST})
  set(slow ${${ARG_PREFIX}_CLASSES_SLOW} ${${ARG_PREFIX}_SUPPORT_SLOW})
  set_source_files_properties(${fast} ${slow} PROPERTIES HEADER_FILE_ONLY ON)
  # The two units, written after each Verilator run from that run's own lists (its P.cmake).
  set(units "${vdir}/${ARG_PREFIX}__fast_unit.cpp" "${vdir}/${ARG_PREFIX}__slow_unit.cpp")
  add_custom_command(OUTPUT ${units}
                     COMMAND "${CMAKE_COMMAND}" "-DVCMAKE=${vdir}/${ARG_PREFIX}.cmake" "-DPREFIX=${ARG_PREFIX}"
                             "-DVDIR=${vdir}" -P "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/verilate_unity_write.cmake"
                     DEPENDS "${vdir}/${ARG_PREFIX}.cmake" "${CMAKE_CURRENT_FUNCTION_LIST_DIR}/verilate_unity_write.cmake"
                     VERBATIM)
  foreach(part fast slow)
    set(unit "${vdir}/${ARG_PREFIX}__${part}_unit.cpp")
    target_sources(${target} PRIVATE "${unit}")
    string(TOUPPER "${part}" upper)
    set_source_files_properties("${unit}" PROPERTIES OBJECT_DEPENDS "${${part}}" COMPILE_OPTIONS "${ARG_OPT_${upper}}")
  endforeach()
endfunction()
