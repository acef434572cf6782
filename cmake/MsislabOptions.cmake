# One place for the language standard and warnings of every msislab target.
function(msislab_target_options target)
  target_compile_features(${target} PUBLIC cxx_std_17)
  set_target_properties(${target} PROPERTIES CXX_EXTENSIONS OFF)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                                           -Wno-sign-conversion)
  if(MSISLAB_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# msislab_glue_code(<target>): code whose speed is not what a user waits for (the commands'
# options and glue, the pages, the settings' YAML, the tools' own mains, the tests' assertions and
# fixtures) compiles at -O1 in Release builds; the libraries that compute (slam, sim, eval,
# geometry, stats, io, dataset, results, plot) stay at -O3. Without fast-math the optimisation
# level does not change a floating-point result, so the outputs are the same bytes
# (docs/architecture.md, "Build notes").
function(msislab_glue_code target)
  if(CMAKE_BUILD_TYPE STREQUAL "Release")
    target_compile_options(${target} PRIVATE -O1)
  endif()
endfunction()

# msislab_core_library(<name> <sources...>): the installed library msislab_<name> (msislab::<name>
# in this tree and to find_package(msislab) users), headers included as "<dir>/<file>.hpp" from
# the source tree here and from include/msislab once installed; the language standard and
# warnings of every target.
function(msislab_core_library name)
  add_library(msislab_${name} ${ARGN})
  target_include_directories(msislab_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                             $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/msislab>)
  set_target_properties(msislab_${name} PROPERTIES EXPORT_NAME ${name})
  add_library(msislab::${name} ALIAS msislab_${name})
  msislab_target_options(msislab_${name})
endfunction()
