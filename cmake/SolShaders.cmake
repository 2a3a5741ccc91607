# sol_add_shader: compile a GLSL compute shader to SPIR-V at build time and
# embed it into a target.
#
#   sol_add_shader(<target> <source>
#                  [SYMBOL <identifier>]
#                  [INCLUDE_DIRECTORIES <dir>...]
#                  [DEFINES <NAME[=VALUE]>...]
#                  [OUTPUT_VARIABLE <var>])
#
# glslangValidator compiles <source> (relative to the current source dir) for
# Vulkan 1.2 (SPIR-V 1.5; not vulkan1.3, which emits LocalSizeId), runs the
# SPIRV-Tools validator on the result, and writes a C++ header
#
#   ${CMAKE_CURRENT_BINARY_DIR}/generated/shaders/<identifier>.hpp
#
# holding `const uint32_t <identifier>[] = {...};`. <identifier> defaults to
# the file name made a C identifier plus `_spv` (fill.comp -> fill_comp_spv).
# The header is added to <target>'s sources (so it is generated before the
# target compiles) and ${CMAKE_CURRENT_BINARY_DIR}/generated to its private
# include directories; one .cpp of the target then embeds the code with
#
#   #include <cstdint>
#   #include "shaders/fill_comp_spv.hpp"
#
# Shaders share code through `#include "x.glsl"` (with
# `#extension GL_GOOGLE_include_directive : require`); the including file's
# directory is searched first, then INCLUDE_DIRECTORIES. glslangValidator's
# --depfile tells the build which files were included, so editing an included
# .glsl rebuilds exactly the shaders that include it. OUTPUT_VARIABLE receives
# the header's path.
include_guard(GLOBAL)

find_program(SOL_GLSLANG_VALIDATOR NAMES glslangValidator
  DOC "glslangValidator, the GLSL to SPIR-V compiler (Debian: glslang-tools)")
if(NOT SOL_GLSLANG_VALIDATOR)
  message(FATAL_ERROR
    "glslangValidator not found: it compiles Sol's compute shaders to SPIR-V. "
    "Install it (Debian: apt-get install glslang-tools, or run scripts/install-deps.sh), "
    "point SOL_GLSLANG_VALIDATOR at it, or configure with -DSOL_BUILD_VULKAN=OFF.")
endif()

function(sol_add_shader target source)
  cmake_parse_arguments(PARSE_ARGV 2 ARG "" "SYMBOL;OUTPUT_VARIABLE" "INCLUDE_DIRECTORIES;DEFINES")
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "sol_add_shader(${target} ${source}): unexpected arguments '${ARG_UNPARSED_ARGUMENTS}'")
  endif()
  if(NOT TARGET ${target})
    message(FATAL_ERROR "sol_add_shader: '${target}' is not a target")
  endif()

  # Absolute paths throughout: the depfile then names absolute files, which
  # the Ninja generator takes as they are.
  get_filename_component(source_path "${source}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(NOT EXISTS "${source_path}")
    message(FATAL_ERROR "sol_add_shader: shader source '${source_path}' does not exist")
  endif()
  get_filename_component(source_name "${source_path}" NAME)
  if(ARG_SYMBOL)
    set(symbol "${ARG_SYMBOL}")
  else()
    string(MAKE_C_IDENTIFIER "${source_name}_spv" symbol)
  endif()
  string(MAKE_C_IDENTIFIER "${symbol}" checked)
  if(NOT checked STREQUAL symbol)
    message(FATAL_ERROR "sol_add_shader: SYMBOL '${symbol}' is not a C identifier")
  endif()

  set(generated_dir "${CMAKE_CURRENT_BINARY_DIR}/generated")
  set(header "${generated_dir}/shaders/${symbol}.hpp")
  set(depfile "${generated_dir}/shaders/${symbol}.d")

  set(flags)
  foreach(dir IN LISTS ARG_INCLUDE_DIRECTORIES)
    get_filename_component(dir "${dir}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
    list(APPEND flags "-I${dir}")
  endforeach()
  foreach(define IN LISTS ARG_DEFINES)
    list(APPEND flags "-D${define}")
  endforeach()

  file(RELATIVE_PATH shown "${PROJECT_SOURCE_DIR}" "${source_path}")
  # (Ninja makes an output's folder itself; the Makefile generators do not.)
  file(MAKE_DIRECTORY "${generated_dir}/shaders")
  add_custom_command(
    OUTPUT "${header}"
    COMMAND "${SOL_GLSLANG_VALIDATOR}" --target-env vulkan1.2 --spirv-val --quiet
            ${flags} --vn ${symbol} --depfile "${depfile}" -o "${header}" "${source_path}"
    MAIN_DEPENDENCY "${source_path}"
    DEPENDS "${SOL_GLSLANG_VALIDATOR}"
    DEPFILE "${depfile}"
    COMMENT "Compiling shader ${shown} to SPIR-V (${symbol})"
    VERBATIM)
  target_sources(${target} PRIVATE "${header}")
  target_include_directories(${target} PRIVATE "${generated_dir}")
  if(ARG_OUTPUT_VARIABLE)
    set(${ARG_OUTPUT_VARIABLE} "${header}" PARENT_SCOPE)
  endif()
endfunction()
