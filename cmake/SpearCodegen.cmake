# spear_generate(MODULE name OUT_DIR dir HEADERS h... OUT_VAR var
#                [ROOT dir] [INCLUDE_DIRS d...] [BLUEPRINT_DIR dir] [PYTHON_OUT dir] [PACKAGE name])
#
# Runs the binding generator on a module's reflected headers. The generator names its outputs from the
# header list alone (`list-outputs`), so CMake knows every output at configure time; the outputs are
# rewritten only when their content changes, and a stamp file carries the build dependency.
#
#   ROOT        header paths (and the IR's paths) are relative to it; default ${PROJECT_SOURCE_DIR}.
#               Relative HEADERS are taken relative to it.
#   OUT_DIR     the output root: generated C++ includes its own headers as generated/<module>/cpp/..., so
#               this is <a directory on the include path>/generated.
#   PYTHON_OUT  the module's Python package directory; default ${OUT_DIR}/<module>/python.
#   PACKAGE     the importable name of that package; default spear._<module>.
#
# Usable from another project (a plugin): include() this file from the spear checkout; SPEAR_SOURCE_DIR
# (that checkout, found from this file's location unless set before) supplies the generator and its
# templates. A plugin passes ROOT = its own source directory and the spear checkout in INCLUDE_DIRS, so
# that its headers' `#include "core/world/actor.h"` resolve.

# Captured at include time: inside the function, CMAKE_CURRENT_LIST_DIR is the caller's directory.
if(NOT DEFINED SPEAR_SOURCE_DIR)
  get_filename_component(SPEAR_SOURCE_DIR "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
endif()

# Absolute paths, so that the generator's working directory does not matter and DEPENDS names real files.
function(_spear_absolute out_var base)
  set(result "")
  foreach(path IN LISTS ARGN)
    if(NOT IS_ABSOLUTE "${path}")
      set(path "${base}/${path}")
    endif()
    get_filename_component(path "${path}" ABSOLUTE)
    list(APPEND result "${path}")
  endforeach()
  set(${out_var} ${result} PARENT_SCOPE)
endfunction()

function(spear_generate)
  cmake_parse_arguments(ARG "" "MODULE;OUT_DIR;OUT_VAR;BLUEPRINT_DIR;PYTHON_OUT;PACKAGE;ROOT"
                        "HEADERS;INCLUDE_DIRS" ${ARGN})
  if(NOT Python3_EXECUTABLE)
    message(FATAL_ERROR "spear_generate(${ARG_MODULE}): set Python3_EXECUTABLE (an interpreter with libclang "
                        "and Jinja2) before calling it")
  endif()
  if(NOT ARG_ROOT)
    set(ARG_ROOT ${PROJECT_SOURCE_DIR})
  endif()
  _spear_absolute(root ${CMAKE_CURRENT_SOURCE_DIR} ${ARG_ROOT})
  _spear_absolute(out_dir ${CMAKE_CURRENT_SOURCE_DIR} ${ARG_OUT_DIR})
  _spear_absolute(headers ${root} ${ARG_HEADERS})
  _spear_absolute(include_dirs ${CMAKE_CURRENT_SOURCE_DIR} ${ARG_INCLUDE_DIRS})

  # PYTHONPATH finds the generator in the spear checkout whatever project calls this.
  set(codegen ${CMAKE_COMMAND} -E env PYTHONPATH=${SPEAR_SOURCE_DIR} ${Python3_EXECUTABLE} -m codegen)
  set(common --module ${ARG_MODULE} --root ${root} --out ${out_dir})
  foreach(dir IN LISTS include_dirs)
    list(APPEND common --include-dir ${dir})
  endforeach()
  if(ARG_PYTHON_OUT)
    _spear_absolute(python_out ${CMAKE_CURRENT_SOURCE_DIR} ${ARG_PYTHON_OUT})
    list(APPEND common --python-out ${python_out})
  endif()
  if(ARG_PACKAGE)
    list(APPEND common --package ${ARG_PACKAGE})
  endif()

  execute_process(
    COMMAND ${codegen} list-outputs ${common} ${headers}
    WORKING_DIRECTORY ${SPEAR_SOURCE_DIR}
    OUTPUT_VARIABLE outputs
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "spear_generate(${ARG_MODULE}): the generator could not list its outputs")
  endif()
  string(STRIP "${outputs}" outputs)
  string(REPLACE "\n" ";" outputs "${outputs}")
  file(GLOB templates CONFIGURE_DEPENDS ${SPEAR_SOURCE_DIR}/templates/*.j2)
  file(GLOB generator_sources CONFIGURE_DEPENDS ${SPEAR_SOURCE_DIR}/codegen/*.py)
  set(blueprint_args "")
  set(blueprints "")
  if(ARG_BLUEPRINT_DIR)
    _spear_absolute(blueprint_dir ${CMAKE_CURRENT_SOURCE_DIR} ${ARG_BLUEPRINT_DIR})
    set(blueprint_args --blueprint-dir ${blueprint_dir})
    file(GLOB blueprints CONFIGURE_DEPENDS ${blueprint_dir}/*.json)
  endif()
  # A plugin's generated code includes the engine's generated files for the engine types it uses, chosen
  # from the engine's IR: a change to the engine's API regenerates it.
  set(engine_ir "")
  if(NOT ARG_MODULE STREQUAL "engine" AND EXISTS ${SPEAR_SOURCE_DIR}/generated/engine/reflection.json)
    set(engine_ir ${SPEAR_SOURCE_DIR}/generated/engine/reflection.json)
  endif()
  set(stamp ${CMAKE_CURRENT_BINARY_DIR}/${ARG_MODULE}.codegen.stamp)
  add_custom_command(
    OUTPUT ${stamp}
    BYPRODUCTS ${outputs}
    COMMAND ${codegen} generate ${common} ${blueprint_args} --stamp ${stamp} ${headers}
    DEPENDS ${headers} ${templates} ${generator_sources} ${blueprints} ${engine_ir}
    WORKING_DIRECTORY ${SPEAR_SOURCE_DIR}
    COMMENT "spear codegen: module ${ARG_MODULE}"
    VERBATIM)
  add_custom_target(spear_codegen_${ARG_MODULE} DEPENDS ${stamp})
  set(${ARG_OUT_VAR} ${outputs} PARENT_SCOPE)
endfunction()
