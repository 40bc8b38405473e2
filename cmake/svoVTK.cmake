# VTK for `svo vtk` (apps/vtk_export.cpp) and its test: makes the targets
# VTK::<module> for the modules below and sets SVO_VTK_LIBRARIES to those
# svo_vtk links.
#
# Where libvtk9-dev is installed, VTK's own CMake package provides them. On a
# machine with ParaView's Python (python3-paraview conflicts with python3-vtk9,
# which libvtk9-dev depends on) that package cannot be installed, and VTK's
# package cannot be used either: its targets file checks for programs of
# python3-vtk9, libvtk9-java and vtk9. There the targets are made here from the
# libraries of libvtk9.1 (the runtime, which does not conflict) and the headers
# scripts/setup.sh unpacks from libvtk9-dev into SVO_VTK_INCLUDE_DIR, as it
# unpacks Dear ImGui's backends.
set(svo_vtk_components CommonCore CommonDataModel IOXML IOImage RenderingCore RenderingOpenGL2 InteractionStyle
                       FiltersHyperTree)
find_package(VTK 9 QUIET COMPONENTS ${svo_vtk_components})
if(VTK_FOUND)
  set(SVO_VTK_SOURCE "VTK's CMake package (${VTK_DIR})")
else()
  set(SVO_VTK_INCLUDE_DIR "/usr/local/share/svo/vtk-9.1/include" CACHE PATH
      "VTK 9.1's headers, where VTK's CMake package is not installed (scripts/setup.sh unpacks them beside python3-paraview)")
  if(NOT EXISTS "${SVO_VTK_INCLUDE_DIR}/vtkVersionMacros.h")
    message(FATAL_ERROR "svo vtk needs VTK 9.1: install libvtk9-dev, or, beside python3-paraview, run scripts/setup.sh "
                        "(it unpacks VTK's headers into ${SVO_VTK_INCLUDE_DIR}); or configure with -DSVO_WITH_VTK=OFF")
  endif()
  # The modules svo_vtk and test_vtk call into, and the libraries they link;
  # libvtk9.1 ships each as lib<name>-9.1.so.1.
  set(svo_vtk_linked ${svo_vtk_components} CommonExecutionModel CommonMath CommonMisc CommonTransforms IOCore
                     IOXMLParser ImagingCore RenderingUI FiltersCore FiltersGeneral sys)
  foreach(module IN LISTS svo_vtk_linked)
    if(module STREQUAL "sys")
      set(file vtksys-9.1.so.1)
    else()
      set(file libvtk${module}-9.1.so.1)
    endif()
    find_library(SVO_VTK_${module}_LIBRARY NAMES ${file} lib${file} NO_CACHE REQUIRED)
    add_library(VTK::${module} SHARED IMPORTED)
    set_target_properties(VTK::${module} PROPERTIES IMPORTED_LOCATION "${SVO_VTK_${module}_LIBRARY}"
                                                    INTERFACE_INCLUDE_DIRECTORIES "${SVO_VTK_INCLUDE_DIR}")
  endforeach()
  # Each target brings the modules its headers' inline code calls into.
  set_property(TARGET VTK::CommonDataModel APPEND PROPERTY INTERFACE_LINK_LIBRARIES VTK::CommonCore VTK::CommonMath
                                                                                     VTK::CommonMisc VTK::sys)
  foreach(module IN ITEMS IOXML IOImage RenderingCore FiltersHyperTree)
    set_property(TARGET VTK::${module} APPEND PROPERTY INTERFACE_LINK_LIBRARIES VTK::CommonDataModel
                                                                              VTK::CommonExecutionModel)
  endforeach()
  set(SVO_VTK_SOURCE "VTK 9.1's headers in ${SVO_VTK_INCLUDE_DIR} with libvtk9.1's libraries")
endif()
set(SVO_VTK_LIBRARIES VTK::CommonCore VTK::CommonDataModel VTK::IOXML VTK::IOImage VTK::RenderingCore
                      VTK::RenderingOpenGL2 VTK::InteractionStyle)
message(STATUS "svo vtk: ${SVO_VTK_SOURCE}")
