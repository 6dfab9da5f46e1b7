# `cmake --install <build> --prefix <prefix>`: the phongsim executable, its files (the tree
# base/paths.h finds relative to the executable: share/phongsim with rtl/, configs/, data/,
# scripts/, sweeps/, cmake/; include/phongsim with the headers), the layer libraries and a CMake
# package (find_package(phongsim): imported targets phongsim::base ... phongsim::explore and the
# phongsim::phongsim executable). docs/library.md.
include(CMakePackageConfigHelpers)

set(PHONGSIM_LIBRARIES phongsim_base phongsim_ref phongsim_model phongsim_cosim
    phongsim_pipelines phongsim_render phongsim_explore)
foreach(lib IN LISTS PHONGSIM_LIBRARIES)
  string(REPLACE "phongsim_" "" short "${lib}")
  set_target_properties(${lib} PROPERTIES EXPORT_NAME ${short})
  target_include_directories(${lib} INTERFACE
    "$<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/phongsim>")
endforeach()

install(TARGETS phongsim ${PHONGSIM_LIBRARIES} EXPORT phongsimTargets
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(dir IN LISTS PHONGSIM_DATA_DIRS)
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/${dir}/" DESTINATION "${CMAKE_INSTALL_DATADIR}/phongsim/${dir}"
          USE_SOURCE_PERMISSIONS PATTERN "__pycache__" EXCLUDE)
endforeach()
foreach(dir IN LISTS PHONGSIM_HEADER_DIRS)
  install(DIRECTORY "${PROJECT_SOURCE_DIR}/${dir}/" DESTINATION "${CMAKE_INSTALL_INCLUDEDIR}/phongsim/${dir}"
          FILES_MATCHING PATTERN "*.h")
endforeach()

install(EXPORT phongsimTargets NAMESPACE phongsim:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/phongsim)
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/phongsimConfig.cmake.in"
  "${PROJECT_BINARY_DIR}/phongsimConfig.cmake"
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/phongsim)
write_basic_package_version_file("${PROJECT_BINARY_DIR}/phongsimConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/phongsimConfig.cmake"
              "${PROJECT_BINARY_DIR}/phongsimConfigVersion.cmake"
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/phongsim)
