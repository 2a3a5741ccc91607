# sol_enable_warnings(target): the project's warning set; errors when
# SOL_WARNINGS_AS_ERRORS is on (CI turns it on). -Wmissing-field-initializers
# is off: our aggregates (sol::Camera, SceneObject) give every member a
# default, and brace-initialising the leading ones is how they are meant to
# be used.
function(sol_enable_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
      -Wno-missing-field-initializers)
    if(SOL_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  elseif(MSVC)
    target_compile_options(${target} PRIVATE /W4 $<$<BOOL:${SOL_WARNINGS_AS_ERRORS}>:/WX>)
  endif()
endfunction()
