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
