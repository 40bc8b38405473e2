# Debian ships OpenVDB without a config file, only as a Find module in
# <prefix>/lib/<multiarch>/cmake/OpenVDB, a folder CMake does not search for
# modules. Look for it in the usual prefixes and append it to CMAKE_MODULE_PATH,
# so that find_package(OpenVDB) works both here and in svoConfig.cmake.
# Appended, so a FindOpenVDB.cmake the caller already has on the path wins.
find_path(SVO_OPENVDB_MODULE_DIR FindOpenVDB.cmake
  PATHS ${CMAKE_PREFIX_PATH} ENV CMAKE_PREFIX_PATH ${CMAKE_SYSTEM_PREFIX_PATH}
  PATH_SUFFIXES lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB lib/cmake/OpenVDB lib64/cmake/OpenVDB
  DOC "Folder holding OpenVDB's FindOpenVDB.cmake")
mark_as_advanced(SVO_OPENVDB_MODULE_DIR)
if(SVO_OPENVDB_MODULE_DIR AND NOT SVO_OPENVDB_MODULE_DIR IN_LIST CMAKE_MODULE_PATH)
  list(APPEND CMAKE_MODULE_PATH "${SVO_OPENVDB_MODULE_DIR}")
endif()
