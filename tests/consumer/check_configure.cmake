# Configure-only check, run as `cmake -P` by ctest (package_add_subdirectory,
# package_minimal_configure). Configures SOURCE_DIR into a fresh BINARY_DIR
# with OPTIONS ("|"-separated -D flags), then fails if the configure looked for
# a package that only the optional parts (CLI, VTK, validation, tests) need.
# Also takes GENERATOR, MAKE_PROGRAM, C_COMPILER, CXX_COMPILER, LAUNCHER from
# the calling build.
string(REPLACE "|" ";" options "${OPTIONS}")
file(REMOVE_RECURSE "${BINARY_DIR}")
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BINARY_DIR} -G ${GENERATOR}
          -DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM} -DCMAKE_C_COMPILER=${C_COMPILER}
          -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER} ${options}
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring ${SOURCE_DIR} with ${options} failed (${rc})")
endif()

# find_package leaves <Package>_DIR in the cache once called, found or not.
file(STRINGS "${BINARY_DIR}/CMakeCache.txt" looked_for REGEX "^(VTK|CGAL|CLI11|GTest)_DIR:")
if(looked_for)
  list(JOIN looked_for "\n  " looked_for)
  message(FATAL_ERROR "the configure looked for optional packages:\n  ${looked_for}")
endif()
message(STATUS "configured without VTK, CGAL, CLI11 or GoogleTest (core reads glTF through nlohmann-json)")
