# What each pipeline's RTL is made of, and how one configuration of it becomes a plugin (a shared
# module the phongsim tools dlopen, see sim/cosim/rtl_library.h). Used by the main build for configs/
# and by sim/cosim/rtl_build/ for configurations Verilated on demand, so both build the same way.
#
# Requires PHONGSIM_SOURCE_DIR; call phongsim_find_rtl_tools() before adding plugins.

# Finds what a plugin build needs and sets PHONGSIM_PYTHON (3.11+, for tomllib; Debian's
# /usr/bin/python3 first, since a python3 earlier in PATH may be a separate install).
macro(phongsim_find_rtl_tools)
  find_package(verilator REQUIRED HINTS $ENV{VERILATOR_ROOT})
  find_package(fmt REQUIRED)
  find_package(ZLIB REQUIRED)
  find_package(Threads REQUIRED)
  if(EXISTS /usr/bin/python3 AND NOT Python3_EXECUTABLE)
    set(Python3_EXECUTABLE /usr/bin/python3)
  endif()
  find_package(Python3 3.11 REQUIRED COMPONENTS Interpreter)
  set(PHONGSIM_PYTHON "${Python3_EXECUTABLE}")
endmacro()

# phongsim_config_name(<configs/pipeline/name.toml> <pipeline-var> <name-var>)
function(phongsim_config_name CONFIG PIPELINE_VAR NAME_VAR)
  get_filename_component(dir "${CONFIG}" DIRECTORY)
  get_filename_component(pipeline "${dir}" NAME)
  get_filename_component(name "${CONFIG}" NAME_WE)
  set(${PIPELINE_VAR} ${pipeline} PARENT_SCOPE)
  set(${NAME_VAR} ${name} PARENT_SCOPE)
endfunction()

set(PHONGSIM_RTL_COMMON
    rtl/common/fx_pkg.sv
    rtl/common/fx_resize.sv
    rtl/common/fx_rq.sv
    rtl/common/fx_add.sv
    rtl/common/fx_sub.sv
    rtl/common/fx_mul.sv
    rtl/common/fx_neg.sv
    rtl/common/fx_abs.sv
    rtl/common/fx_scale.sv
    rtl/common/fx_clamp01.sv
    rtl/common/fx_dot3.sv
    rtl/common/pipe_ctrl.sv
    rtl/common/pipe_delay.sv
    rtl/common/fdiff_acc.sv
    rtl/common/stream_skid.sv)

# Per pipeline: top module and its sources (package first).
set(PHONGSIM_RTL_lirp_TOP lirp_unit)
set(PHONGSIM_RTL_lirp_SOURCES ${PHONGSIM_RTL_COMMON} rtl/lirp/lirp_core.sv rtl/lirp/lirp_unit.sv)

set(PHONGSIM_RTL_lyon_TOP lyon_top)
set(PHONGSIM_RTL_lyon_SOURCES ${PHONGSIM_RTL_COMMON} rtl/lirp/lirp_core.sv rtl/lyon/lyon_norm.sv
    rtl/lyon/lyon_x.sv rtl/lyon/lyon_shape.sv rtl/lyon/lyon_top.sv)

set(PHONGSIM_RTL_kb_TOP kb_engine)
set(PHONGSIM_RTL_kb_SOURCES ${PHONGSIM_RTL_COMMON} rtl/kb/kb_engine.sv)

set(PHONGSIM_RTL_quad_TOP quad_walker)
set(PHONGSIM_RTL_quad_SOURCES ${PHONGSIM_RTL_COMMON} rtl/quad/quad_channel.sv rtl/quad/quad_walker.sv)

set(PHONGSIM_PIPELINES lirp lyon kb quad)

# phongsim_rtl_sources(<pipeline> <out-var>): absolute paths of the pipeline's RTL sources.
function(phongsim_rtl_sources PIPELINE OUT)
  if(NOT DEFINED PHONGSIM_RTL_${PIPELINE}_TOP)
    message(FATAL_ERROR "unknown pipeline '${PIPELINE}' (known: ${PHONGSIM_PIPELINES})")
  endif()
  set(files)
  foreach(f IN LISTS PHONGSIM_RTL_${PIPELINE}_SOURCES)
    list(APPEND files "${PHONGSIM_SOURCE_DIR}/${f}")
  endforeach()
  set(${OUT} ${files} PARENT_SCOPE)
endfunction()

# phongsim_config_gflags(<config.toml> <out-var>): the configuration's -G parameters as a list.
function(phongsim_config_gflags CONFIG OUT)
  execute_process(
    COMMAND "${PHONGSIM_PYTHON}" "${PHONGSIM_SOURCE_DIR}/scripts/config_gflags.py" "${CONFIG}"
    OUTPUT_VARIABLE flags
    ERROR_VARIABLE err
    RESULT_VARIABLE rc
    OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(rc)
    message(FATAL_ERROR "${err}")
  endif()
  string(REPLACE "\n" ";" flags "${flags}")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
               "${CONFIG}" "${PHONGSIM_SOURCE_DIR}/scripts/config_gflags.py")
  set(${OUT} ${flags} PARENT_SCOPE)
endfunction()

# phongsim_add_verilator_runtime(<target>): the Verilator runtime as one shared library, so the
# plugins of a build share it instead of each compiling its own copy (defines as verilate()
# uses them with TRACE_FST).
function(phongsim_add_verilator_runtime TARGET)
  add_library(${TARGET} SHARED
    "${VERILATOR_ROOT}/include/verilated.cpp"
    "${VERILATOR_ROOT}/include/verilated_fst_c.cpp"
    "${VERILATOR_ROOT}/include/verilated_threads.cpp")
  target_include_directories(${TARGET} PUBLIC
    "${VERILATOR_ROOT}/include" "${VERILATOR_ROOT}/include/vltstd")
  target_compile_definitions(${TARGET} PUBLIC
    VM_COVERAGE=0 VM_SC=0 VM_TRACE=1 VM_TRACE_FST=1 VM_TRACE_VCD=0)
  target_compile_features(${TARGET} PUBLIC cxx_std_20)
  target_link_libraries(${TARGET} PUBLIC ZLIB::ZLIB Threads::Threads)
endfunction()

# phongsim_add_rtl_plugin(<target> <pipeline> <config.toml> <output-dir> [RUNTIME <lib>]):
# Verilates the pipeline's top with the configuration's parameters into <output-dir>/<target>.so.
# With RUNTIME the plugin links that shared Verilator runtime instead of compiling its own.
# Sets <target>_GFLAGS in the caller's scope (space-separated, as the plugin reports them).
function(phongsim_add_rtl_plugin TARGET PIPELINE CONFIG OUTPUT_DIR)
  cmake_parse_arguments(ARG "" "RUNTIME" "" ${ARGN})
  phongsim_rtl_sources(${PIPELINE} sources)
  phongsim_config_gflags("${CONFIG}" gflags)
  string(REPLACE ";" " " gflags_text "${gflags}")
  set(top ${PHONGSIM_RTL_${PIPELINE}_TOP})

  add_library(${TARGET} MODULE "${PHONGSIM_SOURCE_DIR}/sim/pipelines/${PIPELINE}_dut.cpp")
  set_target_properties(${TARGET} PROPERTIES
    PREFIX ""
    LIBRARY_OUTPUT_DIRECTORY "${OUTPUT_DIR}"
    POSITION_INDEPENDENT_CODE ON
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  target_compile_features(${TARGET} PRIVATE cxx_std_20)
  target_include_directories(${TARGET} PRIVATE "${PHONGSIM_SOURCE_DIR}")
  target_compile_definitions(${TARGET} PRIVATE "PHONGSIM_RTL_GFLAGS=\"${gflags_text}\"")
  # Fail at link time, not at dlopen, on a missing symbol; keep the Verilator runtime private to
  # each plugin so several configurations can be loaded into one process.
  target_link_options(${TARGET} PRIVATE -Wl,-z,defs -Wl,--exclude-libs,ALL)
  target_link_libraries(${TARGET} PRIVATE fmt::fmt ZLIB::ZLIB Threads::Threads)
  verilate(${TARGET}
    SOURCES ${sources}
    TOP_MODULE ${top}
    PREFIX V${top}
    TRACE_FST
    VERILATOR_ARGS ${gflags} --assert -Wno-fatal -O3 -x-assign fast -x-initial fast)
  if(ARG_RUNTIME)
    get_target_property(plugin_sources ${TARGET} SOURCES)
    list(FILTER plugin_sources EXCLUDE REGEX "^${VERILATOR_ROOT}/include/[^/]*\\.cpp$")
    set_property(TARGET ${TARGET} PROPERTY SOURCES ${plugin_sources})
    target_link_libraries(${TARGET} PRIVATE ${ARG_RUNTIME})
  endif()
  set(${TARGET}_GFLAGS "${gflags_text}" PARENT_SCOPE)
endfunction()
