# Install layout and the svo CMake package (find_package(svo CONFIG)), with
# GNUInstallDirs' folders (lib is lib/<multiarch> under the /usr prefix):
#   include/svo/...              public headers of every layer
#   lib/libsvo_core.a, libsvo_gl_{device,voxelize,fields,view,nanovdb}.a, libsvo_vdb_io.a, libsvo_svo.a
#   lib/cmake/svo/               svoConfig.cmake, svoConfigVersion.cmake, svoTargets*.cmake,
#                                svoOpenVDBModulePath.cmake
#   bin/svo                      with SVO_BUILD_CLI
#   lib/svo/libsvo_vtk.so        with SVO_WITH_VTK: the module `svo vtk` loads
# The shaders are compiled into the GL layers' libraries, so nothing else is needed at run time.
include(CMakePackageConfigHelpers)
set(SVO_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/svo" CACHE STRING
    "Where svoConfig.cmake goes, relative to the install prefix")
mark_as_advanced(SVO_INSTALL_CMAKEDIR)

install(TARGETS svo_core svo_gl_device svo_gl_voxelize svo_gl_fields svo_gl_view svo_gl_nanovdb svo_gl svo_vdb_io svo_svo
        EXPORT svoTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
# Whole trees: overlap.h includes overlap.glsl, which is shared with the shaders.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/
                  ${PROJECT_SOURCE_DIR}/gl/device/include/ ${PROJECT_SOURCE_DIR}/gl/voxelize/include/
                  ${PROJECT_SOURCE_DIR}/gl/fields/include/ ${PROJECT_SOURCE_DIR}/gl/view/include/
                  ${PROJECT_SOURCE_DIR}/gl/nanovdb/include/
                  ${PROJECT_SOURCE_DIR}/vdb_io/convert/include/ ${PROJECT_SOURCE_DIR}/vdb_io/voxelizer/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT svoTargets NAMESPACE svo:: DESTINATION ${SVO_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/svoConfig.cmake.in "${PROJECT_BINARY_DIR}/svoConfig.cmake"
  INSTALL_DESTINATION ${SVO_INSTALL_CMAKEDIR})
write_basic_package_version_file("${PROJECT_BINARY_DIR}/svoConfigVersion.cmake"
  COMPATIBILITY SameMajorVersion)
install(FILES "${PROJECT_BINARY_DIR}/svoConfig.cmake" "${PROJECT_BINARY_DIR}/svoConfigVersion.cmake"
              ${PROJECT_SOURCE_DIR}/cmake/svoOpenVDBModulePath.cmake
        DESTINATION ${SVO_INSTALL_CMAKEDIR})

if(TARGET svo)
  install(TARGETS svo RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
if(TARGET svo_vtk)
  # Where `svo vtk` looks for it: SVO_VTK_MODULE_FROM_BIN from bin (apps/CMakeLists.txt).
  install(TARGETS svo_vtk LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/svo)
endif()
