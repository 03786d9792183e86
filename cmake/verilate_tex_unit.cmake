# verilate_tex_unit(TARGET PREFIX LOG2_W LOG2_H [CW bits] [TRACE_FST] [FORMATS] [CUBES] [CACHED BW BH LINES FIFO MEM_W MISS]):
# tex_unit of rtl/ verilated into TARGET as class PREFIX, for textures up to 2^LOG2_W x 2^LOG2_H
# with CW-bit channels (default 8); with CACHED, tex_unit_cached with those BLOCK_W, BLOCK_H,
# LINES, FIFO_DEPTH, MEM_W and MISS_DEPTH; with FORMATS also the block decoders and the sRGB tables
# (BLOCK_FORMATS = SRGB = 1: 8-bit channels in memory, CW 16), else neither; with CUBES cube maps
# (CUBE_MAPS = 1, else 0). (The decoders are
# functions that the taps call only for block and sRGB texels: they cost simulation time only in
# the clocks that use them.)
# One set of options for every build: -Wall (make lint keeps it at zero warnings), assertions on,
# registers without reset start random (the design must not rely on zero initialisation),
# single-threaded, C++ at -O2 (Verilator's default -Os is about 1.5x slower).
# TEX_VERILATOR_EXTRA_ARGS (a cache variable, empty by default) adds options to every configuration,
# e.g. -DTEX_VERILATOR_EXTRA_ARGS=--prof-cfuncs in a separate build tree to see which always
# block the simulation time goes to (docs/performance.md, "Profiling the Verilated RTL").
set(TEX_VERILATOR_EXTRA_ARGS "" CACHE STRING "extra Verilator options for every tex_unit configuration")
include(${CMAKE_CURRENT_LIST_DIR}/verilate_unity.cmake)

function(verilate_tex_unit target prefix log2_w log2_h)
  cmake_parse_arguments(ARG "TRACE_FST;FORMATS;CUBES" "CW" "CACHED" ${ARGN})
  if(NOT ARG_CW)
    set(ARG_CW 8)
  endif()
  # Sources in compile order from rtl/tex_files.f (comment and option lines skipped), waivers first.
  # The list starts with tex_unit's own files, through rtl/tex_unit.sv: an on-chip configuration
  # takes those only (Verilator compiles every package it reads, used or not: the decoders' add
  # about 12 s of compiling to each configuration).
  set(file_list ${PROJECT_SOURCE_DIR}/rtl/tex_files.f)
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${file_list})
  file(STRINGS ${file_list} lines)
  set(sources "")
  foreach(line ${lines})
    string(STRIP "${line}" line)
    if(line MATCHES "^[^#/+-]")
      list(APPEND sources ${PROJECT_SOURCE_DIR}/${line})
      if(NOT ARG_CACHED AND line STREQUAL "rtl/tex_unit.sv")
        break()
      endif()
    endif()
  endforeach()
  file(GLOB waivers CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/rtl/*.vlt)
  set(mode "")
  if(ARG_TRACE_FST)
    list(APPEND mode TRACE_FST)
  endif()
  set(top tex_unit)
  set(cache_params "")
  if(ARG_CACHED)
    set(top tex_unit_cached)
    list(GET ARG_CACHED 0 bw)
    list(GET ARG_CACHED 1 bh)
    list(GET ARG_CACHED 2 lines)
    list(GET ARG_CACHED 3 fifo)
    list(GET ARG_CACHED 4 mem_w)
    list(GET ARG_CACHED 5 miss)
    set(formats 0)
    if(ARG_FORMATS)
      set(formats 1)
    endif()
    set(cubes 0)
    if(ARG_CUBES)
      set(cubes 1)
    endif()
    set(cache_params -GBLOCK_W=${bw} -GBLOCK_H=${bh} -GLINES=${lines} -GFIFO_DEPTH=${fifo} -GMEM_W=${mem_w}
                     -GMISS_DEPTH=${miss} -GBLOCK_FORMATS=${formats} -GSRGB=${formats} -GCUBE_MAPS=${cubes})
  endif()
  verilate_unity(${target} ${mode}
    PREFIX ${prefix}
    TOP_MODULE ${top}
    SOURCES ${waivers} ${sources}
    VERILATOR_ARGS -Wall --assert -I${PROJECT_SOURCE_DIR}/rtl -GMAX_LOG2_W=${log2_w} -GMAX_LOG2_H=${log2_h} -GCW=${ARG_CW} -GTAG_W=16
                   ${cache_params}
                   --x-assign unique --x-initial unique ${TEX_VERILATOR_EXTRA_ARGS}
    OPT_FAST -O2
    OPT_GLOBAL -O2
    OPT_SLOW -O1)
endfunction()
