include(CMakePackageConfigHelpers)

set_target_properties(collide2d_strict_fp PROPERTIES EXPORT_NAME strict_fp)

set(COLLIDE2D_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/collide2d)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/src/collide2d/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/collide2d
        FILES_MATCHING PATTERN "*.hpp"
        PATTERN "run_file_hdf5.hpp" EXCLUDE
        PATTERN "run_file_raw.hpp" EXCLUDE)
install(FILES ${PROJECT_BINARY_DIR}/src/generated/collide2d/version.hpp DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/collide2d)

install(TARGETS collide2d_core collide2d_strict_fp EXPORT collide2dTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS collide2d RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The datasets `collide2d study` reads by default (src/cli/datasets.hpp finds them here).
install(FILES ${PROJECT_SOURCE_DIR}/datasets/hard/hard_queries.jsonl DESTINATION ${CMAKE_INSTALL_DATADIR}/collide2d/datasets/hard)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/datasets/scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/collide2d/datasets/scenes
        FILES_MATCHING PATTERN "*.json")
install(EXPORT collide2dTargets NAMESPACE collide2d:: DESTINATION ${COLLIDE2D_CMAKE_DIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/collide2dConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/collide2dConfig.cmake
                              INSTALL_DESTINATION ${COLLIDE2D_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/collide2dConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/collide2dConfig.cmake ${PROJECT_BINARY_DIR}/collide2dConfigVersion.cmake
        DESTINATION ${COLLIDE2D_CMAKE_DIR})
