# How phongsim turns a design into an RTL plugin (a shared module the phongsim tools dlopen, see
# sim/cosim/rtl_plugin.h). phongsim writes a small CMake project that includes this file and
# calls these functions, one plugin per design; nothing here knows a pipeline.
#
# Requires PHONGSIM_INCLUDE_DIR (the tree the adapter's #includes resolve in: the sources, or an
# install's include/phongsim); call phongsim_find_rtl_tools() before adding plugins.

macro(phongsim_find_rtl_tools)
  find_package(verilator REQUIRED HINTS $ENV{VERILATOR_ROOT})
  find_package(fmt REQUIRED)
  find_package(ZLIB REQUIRED)
  find_package(Threads REQUIRED)
endmacro()

set(PHONGSIM_VERILATED_DEFINES VM_COVERAGE=0 VM_SC=0 VM_TRACE=1 VM_TRACE_FST=1 VM_TRACE_VCD=0)

# phongsim_add_verilator_runtime(<target>): the Verilator runtime as one shared library, so the
# plugins share it instead of each compiling its own copy (defines as verilate() uses them with
# TRACE_FST).
function(phongsim_add_verilator_runtime TARGET)
  add_library(${TARGET} SHARED
    "${VERILATOR_ROOT}/include/verilated.cpp"
    "${VERILATOR_ROOT}/include/verilated_fst_c.cpp"
    "${VERILATOR_ROOT}/include/verilated_threads.cpp")
  set_target_properties(${TARGET} PROPERTIES OUTPUT_NAME phongsim_verilated)
  target_include_directories(${TARGET} PUBLIC
    "${VERILATOR_ROOT}/include" "${VERILATOR_ROOT}/include/vltstd")
  target_compile_definitions(${TARGET} PUBLIC ${PHONGSIM_VERILATED_DEFINES})
  target_compile_features(${TARGET} PUBLIC cxx_std_20)
  target_link_libraries(${TARGET} PUBLIC ZLIB::ZLIB Threads::Threads)
endfunction()

# phongsim_import_verilator_runtime(<target> <libphongsim_verilated.so>): one built before.
function(phongsim_import_verilator_runtime TARGET LIBRARY)
  add_library(${TARGET} SHARED IMPORTED)
  set_target_properties(${TARGET} PROPERTIES IMPORTED_LOCATION "${LIBRARY}")
  target_include_directories(${TARGET} INTERFACE
    "${VERILATOR_ROOT}/include" "${VERILATOR_ROOT}/include/vltstd")
  target_compile_definitions(${TARGET} INTERFACE ${PHONGSIM_VERILATED_DEFINES})
  target_link_libraries(${TARGET} INTERFACE ZLIB::ZLIB Threads::Threads)
endfunction()

# phongsim_add_rtl_plugin(<target> TOP <module> ADAPTER <adapter.cpp> OUTPUT_DIR <dir>
#                         RUNTIME <runtime target> RUNTIME_RPATH <rpath>
#                         [COVERAGE] SOURCES <sv files...> VERILATOR_ARGS <args...>):
# Verilates TOP from SOURCES into <dir>/<target>.so, compiled with the generated ADAPTER (which
# binds ports to model fields) and linked with the shared Verilator runtime, found at run time
# through RUNTIME_RPATH. COVERAGE (with --coverage-line/-toggle in VERILATOR_ARGS) compiles
# Verilator's coverage runtime in: the shared runtime has none.
function(phongsim_add_rtl_plugin TARGET)
  cmake_parse_arguments(ARG "COVERAGE" "TOP;ADAPTER;OUTPUT_DIR;RUNTIME;RUNTIME_RPATH"
                        "SOURCES;VERILATOR_ARGS" ${ARGN})
  add_library(${TARGET} MODULE "${ARG_ADAPTER}")
  set_target_properties(${TARGET} PROPERTIES
    PREFIX ""
    LIBRARY_OUTPUT_DIRECTORY "${ARG_OUTPUT_DIR}"
    POSITION_INDEPENDENT_CODE ON
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    BUILD_RPATH "${ARG_RUNTIME_RPATH}")
  target_compile_features(${TARGET} PRIVATE cxx_std_20)
  target_include_directories(${TARGET} PRIVATE "${PHONGSIM_INCLUDE_DIR}")
  # Fail at link time, not at dlopen, on a missing symbol.
  target_link_options(${TARGET} PRIVATE -Wl,-z,defs)
  target_link_libraries(${TARGET} PRIVATE fmt::fmt ZLIB::ZLIB Threads::Threads)
  # The simulation threads the model was Verilated for (--threads N; 1 without it): the
  # adapter's VerilatedContext asks for that many, where Verilator's default (one per hardware
  # thread) starts a worker thread for every DUT made, each shard of a co-simulation making one.
  # Verilator takes -threads as well as --threads.
  set(threads 1)
  set(next_is_threads OFF)
  foreach(arg IN LISTS ARG_VERILATOR_ARGS)
    if(next_is_threads)
      set(threads "${arg}")
    endif()
    set(next_is_threads OFF)
    if(arg STREQUAL "--threads" OR arg STREQUAL "-threads")
      set(next_is_threads ON)
    endif()
  endforeach()
  target_compile_definitions(${TARGET} PRIVATE PHONGSIM_VERILATED_THREADS=${threads})
  verilate(${TARGET}
    SOURCES ${ARG_SOURCES}
    TOP_MODULE ${ARG_TOP}
    PREFIX V${ARG_TOP}
    TRACE_FST
    VERILATOR_ARGS ${ARG_VERILATOR_ARGS})
  # Link the shared runtime instead of the copy verilate() adds to every target.
  get_target_property(plugin_sources ${TARGET} SOURCES)
  list(FILTER plugin_sources EXCLUDE REGEX "^${VERILATOR_ROOT}/include/[^/]*\\.cpp$")
  # Verilator writes a dozen or more small .cpp files, and each spends most of its compile time
  # parsing the same Verilator headers: they compile as two translation units instead, one with
  # the per-cycle code, one with the slow path (construction and initial evaluation, run once;
  # -O0, as GCC's optimizer spends minutes on the huge functions of coverage builds). Halves a
  # plugin's compile time (docs/cosim.md). The generated files stay sources, header-only, so
  # that verilation runs before the two compile.
  set(fast_includes "")
  set(slow_includes "")
  foreach(source IN LISTS plugin_sources)
    if(source MATCHES "__Slow\\.cpp$")
      string(APPEND slow_includes "#include \"${source}\"\n")
    elseif(source MATCHES "/V${ARG_TOP}\\.dir/[^/]*\\.cpp$")
      string(APPEND fast_includes "#include \"${source}\"\n")
    else()
      continue()
    endif()
    set_source_files_properties("${source}" PROPERTIES HEADER_FILE_ONLY ON)
  endforeach()
  if(ARG_COVERAGE)
    string(APPEND slow_includes "#include \"${VERILATOR_ROOT}/include/verilated_cov.cpp\"\n")
  endif()
  set(unity_dir "${CMAKE_CURRENT_BINARY_DIR}/${TARGET}_unity")
  file(WRITE "${unity_dir}/fast.cpp" "${fast_includes}")
  file(WRITE "${unity_dir}/slow.cpp" "${slow_includes}")
  set_source_files_properties("${unity_dir}/slow.cpp" PROPERTIES COMPILE_OPTIONS -O0)
  list(APPEND plugin_sources "${unity_dir}/fast.cpp" "${unity_dir}/slow.cpp")
  set_property(TARGET ${TARGET} PROPERTY SOURCES ${plugin_sources})
  target_link_libraries(${TARGET} PRIVATE ${ARG_RUNTIME})
endfunction()
