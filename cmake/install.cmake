# `cmake --install build --prefix P`: the libraries, their headers, the data the
# examples play and a CMake package, so an engine's build says
#   find_package(facial CONFIG REQUIRED)
#   target_link_libraries(game PRIVATE facial::runtime)   # or facial::c, facial::engine, facial::importers
# (examples/embed and examples/embed_c; tests/embed_install.cmake builds them).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(FACIAL_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/facial)
set(FACIAL_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/facial/data)

set_target_properties(eng_core PROPERTIES EXPORT_NAME core)
set_target_properties(facial PROPERTIES EXPORT_NAME runtime)
set_target_properties(facial_c PROPERTIES EXPORT_NAME c)
install(TARGETS eng_core facial facial_c EXPORT facialRuntime
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT facialRuntime NAMESPACE facial:: FILE facialRuntimeTargets.cmake DESTINATION ${FACIAL_INSTALL_CMAKEDIR})

set_target_properties(eng_scene PROPERTIES EXPORT_NAME scene)
set_target_properties(eng_image PROPERTIES EXPORT_NAME image)
set_target_properties(eng_view PROPERTIES EXPORT_NAME view)
set_target_properties(eng_vk PROPERTIES EXPORT_NAME vk)
set_target_properties(facial_importers PROPERTIES EXPORT_NAME importers)
install(TARGETS eng_scene eng_image eng_view eng_vk facial_engine facial_importers EXPORT facialEngine
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT facialEngine NAMESPACE facial:: FILE facialEngineTargets.cmake DESTINATION ${FACIAL_INSTALL_CMAKEDIR})

# Headers keep their source paths (#include "facial/runtime/..." / "engine/...");
# the public API is include/facial/*.h. detail/ folders hold implementation
# headers (the graph JSON readers, which throw internally) and stay out.
install(DIRECTORY facial/include/facial DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY importers/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/importers FILES_MATCHING PATTERN "*.h")
install(DIRECTORY facial/runtime DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/facial FILES_MATCHING PATTERN "*.h"
        PATTERN detail EXCLUDE)
foreach(part core scene image view vk)
  install(DIRECTORY engine/${part} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/engine FILES_MATCHING PATTERN "*.h"
          PATTERN detail EXCLUDE)
endforeach()

install(DIRECTORY data/graphs data/timelines data/rigmaps DESTINATION ${FACIAL_INSTALL_DATADIR})
install(FILES data/expressions.json DESTINATION ${FACIAL_INSTALL_DATADIR})

configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/facialConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/facialConfig.cmake
  INSTALL_DESTINATION ${FACIAL_INSTALL_CMAKEDIR}
  PATH_VARS FACIAL_INSTALL_DATADIR)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/facialConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/facialConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/facialConfigVersion.cmake
        DESTINATION ${FACIAL_INSTALL_CMAKEDIR})
