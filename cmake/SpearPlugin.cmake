# spear_add_plugin(<name> HEADERS header... [SOURCES source...] [INCLUDE_DIRS dir...] [PYTHON_DIR dir])
#
# Builds a spear plugin from its reflected headers: the generator runs on HEADERS (and again whenever one
# changes), and the build produces the Python package <PYTHON_DIR>/<name>/ (default PYTHON_DIR:
# <build>/python) holding
#   lib<name>.so         the plugin's classes and their registry (loaded by the in-process engine and by
#                        spear-server --plugin, through sp::plugin::load)
#   _<name>.*.so         the pybind11 bindings used in-process
#   api.py, api.pyi, rpc.py, type_codes.py, __init__.py, py.typed   the typed API (mypy reads api.pyi)
# Put <PYTHON_DIR> on sys.path (and MYPYPATH) and call spear.Instance.load_plugin("<name>").
function(spear_add_plugin name)
  cmake_parse_arguments(ARG "" "PYTHON_DIR" "HEADERS;SOURCES;INCLUDE_DIRS" ${ARGN})
  if(NOT ARG_HEADERS)
    message(FATAL_ERROR "spear_add_plugin(${name}): HEADERS is required (the plugin's reflected headers)")
  endif()
  if(NOT name MATCHES "^[a-z_][a-z0-9_]*$")
    message(FATAL_ERROR "spear_add_plugin(${name}): the name must be a Python package name (lower_case)")
  endif()
  if(NOT ARG_PYTHON_DIR)
    set(ARG_PYTHON_DIR ${CMAKE_CURRENT_BINARY_DIR}/python)
  endif()
  set(package_dir ${ARG_PYTHON_DIR}/${name})
  set(headers "")
  foreach(header IN LISTS ARG_HEADERS)
    get_filename_component(path ${header} ABSOLUTE BASE_DIR ${CMAKE_CURRENT_SOURCE_DIR})
    list(APPEND headers ${path})
  endforeach()
  get_target_property(eigen_includes Eigen3::Eigen INTERFACE_INCLUDE_DIRECTORIES)
  spear_generate(MODULE ${name} ROOT ${CMAKE_CURRENT_SOURCE_DIR} OUT_DIR ${CMAKE_CURRENT_BINARY_DIR}/generated
                 PYTHON_OUT ${package_dir} PACKAGE ${name} HEADERS ${headers}
                 INCLUDE_DIRS ${SPEAR_SOURCE_DIR} ${eigen_includes} ${ARG_INCLUDE_DIRS} OUT_VAR outputs)
  # Per reflected header, a registry file (<stem>.gen.cpp, in the plugin library) and bindings
  # (<stem>.bind.gen.cpp, in its Python module, with module.gen.cpp calling them).
  set(registry ${outputs})
  list(FILTER registry INCLUDE REGEX "\\.gen\\.cpp$")
  list(FILTER registry EXCLUDE REGEX "/(module|[^/]*\\.bind)\\.gen\\.cpp$")
  set(bindings ${outputs})
  list(FILTER bindings INCLUDE REGEX "/(module|[^/]*\\.bind)\\.gen\\.cpp$")

  # Its in-process Python bindings. Defined before the library, so that ninja (which starts work in the
  # order it finds it) compiles the binding files, the longest after a header edit, first: the loop from
  # an edit to a usable module is the longest compile, not that compile after the others.
  set(SPEAR_PLUGIN_NAME ${name})
  configure_file(${SPEAR_SOURCE_DIR}/cmake/plugin_module.cpp.in ${CMAKE_CURRENT_BINARY_DIR}/${name}_module.cpp
                 @ONLY)
  pybind11_add_module(_${name} MODULE ${CMAKE_CURRENT_BINARY_DIR}/${name}_module.cpp ${bindings})
  target_link_libraries(_${name} PRIVATE ${name} spear::spear_pybind)
  # pybind11 and the bridge, parsed once for all the plugin's binding files (a header's: 8.0 -> 6.1 s).
  target_precompile_headers(_${name} PRIVATE <pybind11/pybind11.h> <array> <core/pybind/bridge.h>)
  set_target_properties(_${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY $<1:${package_dir}>)

  # The plugin itself: its sources and generated registry, over the engine's shared library.
  add_library(${name} SHARED ${ARG_SOURCES} ${registry})
  add_dependencies(${name} spear_codegen_${name})
  target_include_directories(${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_BINARY_DIR}
                             ${ARG_INCLUDE_DIRS})
  target_link_libraries(${name} PUBLIC spear::spear_core)
  # $<1:...>: the package directory itself, also with multi-config generators (no per-config subfolder).
  set_target_properties(${name} PROPERTIES LIBRARY_OUTPUT_DIRECTORY $<1:${package_dir}>)
  file(WRITE ${package_dir}/py.typed "")
endfunction()
