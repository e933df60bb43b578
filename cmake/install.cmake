# cmake --install build --prefix P: the libraries, the headers under P/include/refract/
# (geometry/, core/, validation/, experiments/: #include <refract/core/x.h>), the
# image module (P/lib/refract, found by the installed programs without the build tree),
# the `refract` executable, the scenes (P/share/refract), the Python package, and the CMake package
# refract (P/lib/cmake/refract) with the targets refract::geometry, refract::core,
# refract::validation and refract::experiments.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(_refract_libs refract_geometry refract_core refract_validation refract_experiments)
foreach(_t IN LISTS _refract_libs)
  string(REPLACE "refract_" "" _name ${_t})
  set_target_properties(${_t} PROPERTIES EXPORT_NAME ${_name})
endforeach()
install(TARGETS ${_refract_libs} EXPORT refractTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS refract_image_io LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/refract)
install(TARGETS refract RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The scenes, with the validation suite (scenes/validation), where an installed `refract
# validate` and `refract reproduce` look when run outside the checkout (cli/data_dir.h).
install(DIRECTORY scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/refract/scenes)
install(DIRECTORY geometry core validation experiments DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/refract
        FILES_MATCHING PATTERN "*.h")
install(EXPORT refractTargets NAMESPACE refract:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/refract)
set(REFRACT_IMAGE_IO_FILE_NAME ${CMAKE_SHARED_MODULE_PREFIX}refract_image_io${CMAKE_SHARED_MODULE_SUFFIX})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/refractConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/refractConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/refract)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/refractConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/refractConfig.cmake ${PROJECT_BINARY_DIR}/refractConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/image_io_location.cpp
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/refract)

if(REFRACT_BUILD_TESTS)
  set(_py "")
  if(REFRACT_BUILD_PYTHON)
    set(_py -DPYTHON=${Python3_EXECUTABLE})
  endif()
  add_test(NAME install:consumer
           COMMAND ${CMAKE_COMMAND} -DBUILD=${PROJECT_BINARY_DIR} -DSOURCE=${PROJECT_SOURCE_DIR} ${_py}
                   -P ${PROJECT_SOURCE_DIR}/cmake/test_install.cmake)
  set_tests_properties(install:consumer PROPERTIES LABELS install TIMEOUT 600)
  # The installed module, not the build tree's: nothing under test may read the variable.
  set_property(TEST install:consumer APPEND PROPERTY ENVIRONMENT "REFRACT_IMAGE_IO=")
endif()
