# verilate_tex_unit(TARGET PREFIX LOG2_W LOG2_H [CW bits] [TRACE_FST]): tex_unit of rtl/
# verilated into TARGET as class PREFIX, for textures up to 2^LOG2_W x 2^LOG2_H with CW-bit
# channels (default 8).
# One set of options for every build: -Wall (make lint keeps it at zero warnings), assertions on,
# registers without reset start random (the design must not rely on zero initialisation),
# single-threaded, C++ at -O2 (Verilator's default -Os is about 1.5x slower).
find_package(verilator 5 REQUIRED HINTS /usr/share/verilator $ENV{VERILATOR_ROOT})

function(verilate_tex_unit target prefix log2_w log2_h)
  cmake_parse_arguments(ARG "TRACE_FST" "CW" "" ${ARGN})
  if(NOT ARG_CW)
    set(ARG_CW 8)
  endif()
  # Sources in compile order from rtl/tex_files.f (comment and option lines skipped), waivers first.
  set(file_list ${PROJECT_SOURCE_DIR}/rtl/tex_files.f)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${file_list})
  file(STRINGS ${file_list} lines)
  set(sources "")
  foreach(line ${lines})
    string(STRIP "${line}" line)
    if(line MATCHES "^[^#/+-]")
      list(APPEND sources ${PROJECT_SOURCE_DIR}/${line})
    endif()
  endforeach()
  file(GLOB waivers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/rtl/*.vlt)
  set(mode "")
  if(ARG_TRACE_FST)
    list(APPEND mode TRACE_FST)
  endif()
  verilate(${target} ${mode}
    PREFIX ${prefix}
    TOP_MODULE tex_unit
    SOURCES ${waivers} ${sources}
    VERILATOR_ARGS -Wall --assert -GMAX_LOG2_W=${log2_w} -GMAX_LOG2_H=${log2_h} -GCW=${ARG_CW} -GTAG_W=16
                   --x-assign unique --x-initial unique
    OPT_FAST -O2
    OPT_GLOBAL -O2
    OPT_SLOW -O1)
endfunction()
