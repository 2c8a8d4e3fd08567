# spear_generate(MODULE name OUT_DIR dir HEADERS h... [INCLUDE_DIRS d...] [BLUEPRINT_DIR dir] OUT_VAR var)
#
# Runs the binding generator on a module's reflected headers. The generator names its outputs from the
# header list alone (`list-outputs`), so CMake knows every output at configure time; the outputs are
# rewritten only when their content changes, and a stamp file carries the build dependency.
function(spear_generate)
  cmake_parse_arguments(ARG "" "MODULE;OUT_DIR;OUT_VAR;BLUEPRINT_DIR" "HEADERS;INCLUDE_DIRS" ${ARGN})
  set(codegen ${Python3_EXECUTABLE} -m codegen)
  set(common --module ${ARG_MODULE} --root ${PROJECT_SOURCE_DIR} --out ${ARG_OUT_DIR})
  foreach(dir IN LISTS ARG_INCLUDE_DIRS)
    list(APPEND common --include-dir ${dir})
  endforeach()
  execute_process(
    COMMAND ${codegen} list-outputs ${common} ${ARG_HEADERS}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    OUTPUT_VARIABLE outputs
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "spear_generate(${ARG_MODULE}): the generator could not list its outputs")
  endif()
  string(STRIP "${outputs}" outputs)
  string(REPLACE "\n" ";" outputs "${outputs}")
  file(GLOB templates CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/templates/*.j2)
  file(GLOB generator_sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/codegen/*.py)
  set(blueprint_args "")
  set(blueprints "")
  if(ARG_BLUEPRINT_DIR)
    set(blueprint_args --blueprint-dir ${ARG_BLUEPRINT_DIR})
    file(GLOB blueprints CONFIGURE_DEPENDS ${ARG_BLUEPRINT_DIR}/*.json)
  endif()
  set(stamp ${CMAKE_CURRENT_BINARY_DIR}/${ARG_MODULE}.codegen.stamp)
  add_custom_command(
    OUTPUT ${stamp}
    BYPRODUCTS ${outputs}
    COMMAND ${codegen} generate ${common} ${blueprint_args} --stamp ${stamp} ${ARG_HEADERS}
    DEPENDS ${ARG_HEADERS} ${templates} ${generator_sources} ${blueprints}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    COMMENT "spear codegen: module ${ARG_MODULE}"
    VERBATIM)
  add_custom_target(spear_codegen_${ARG_MODULE} DEPENDS ${stamp})
  set(${ARG_OUT_VAR} ${outputs} PARENT_SCOPE)
endfunction()
