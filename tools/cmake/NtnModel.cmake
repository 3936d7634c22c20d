# ntn_add_model(TARGET <target> MODEL <model.toml> [NAME <name>] [NO_DEFINITIONS])
#
# Compiles a TOML model into a constexpr header at build time and gives it to <target>:
#   - runs ntn-modelc (in the ntn-rt tree: rebuilt first when its sources change; from an installed
#     tree, find_package(ntnrt): ntn::ntn-modelc), rerun when the model changes,
#     writing ${CMAKE_CURRENT_BINARY_DIR}/ntn_models/<name>_model.hpp;
#   - adds that directory to the target's include path, and the header to its sources so the
#     target waits for it;
#   - sets NTN_MODEL_HEADER="<name>_model.hpp" and NTN_MODEL_NS=ntn::models::<name> on the target,
#     so a generic main can `#include NTN_MODEL_HEADER` and use `NTN_MODEL_NS::kSpec`.
# NAME defaults to the model file's name without .toml, and must be a C++ identifier: the
# header's namespace is ntn::models::<name> whatever the [model] name in the file is.
# A target that takes several models passes NO_DEFINITIONS for all but one (one macro name can
# only have one value) and includes the others as "<name>_model.hpp".
# Call it in the directory that creates <target> (custom command outputs belong to a directory).
function(ntn_add_model)
  cmake_parse_arguments(PARSE_ARGV 0 ARG "NO_DEFINITIONS" "TARGET;MODEL;NAME" "")
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "ntn_add_model: unexpected arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT ARG_TARGET OR NOT ARG_MODEL)
    message(FATAL_ERROR "ntn_add_model: TARGET and MODEL are required")
  endif()
  if(NOT TARGET ${ARG_TARGET})
    message(FATAL_ERROR "ntn_add_model: '${ARG_TARGET}' is not a target")
  endif()
  get_filename_component(model "${ARG_MODEL}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  if(NOT EXISTS "${model}")
    message(FATAL_ERROR "ntn_add_model: model file '${model}' does not exist")
  endif()
  if(ARG_NAME)
    set(name "${ARG_NAME}")
  else()
    get_filename_component(name "${model}" NAME_WLE)
  endif()
  if(NOT name MATCHES "^[A-Za-z_][A-Za-z0-9_]*$")
    message(FATAL_ERROR "ntn_add_model: NAME '${name}' is not a C++ identifier (give NAME)")
  endif()

  # The model compiler: this build's (in the ntn-rt tree) or the installed one (find_package).
  if(TARGET ntn-modelc)
    set(modelc ntn-modelc)
    set(modelc_dep ntn-modelc)
  elseif(TARGET ntn::ntn-modelc)
    set(modelc ntn::ntn-modelc)
    set(modelc_dep "$<TARGET_FILE:ntn::ntn-modelc>")
  else()
    message(FATAL_ERROR "ntn_add_model: no model compiler (build ntn-rt, or find_package(ntnrt))")
  endif()

  set(dir "${CMAKE_CURRENT_BINARY_DIR}/ntn_models")
  set(header "${dir}/${name}_model.hpp")
  add_custom_command(
    OUTPUT "${header}"
    COMMAND ${modelc} "${model}" -o "${header}" --name "${name}"
    DEPENDS "${model}" ${modelc_dep}
    COMMENT "Compiling model ${ARG_MODEL} -> ntn_models/${name}_model.hpp"
    VERBATIM)
  target_sources(${ARG_TARGET} PRIVATE "${header}")
  target_include_directories(${ARG_TARGET} PRIVATE "${dir}")
  target_link_libraries(${ARG_TARGET} PRIVATE ntn::kernel)
  if(NOT ARG_NO_DEFINITIONS)
    get_target_property(defs ${ARG_TARGET} COMPILE_DEFINITIONS)
    if(defs AND "${defs}" MATCHES "NTN_MODEL_HEADER=")
      message(FATAL_ERROR "ntn_add_model: '${ARG_TARGET}' already has a model header; pass "
                          "NO_DEFINITIONS for its other models")
    endif()
    target_compile_definitions(${ARG_TARGET} PRIVATE "NTN_MODEL_HEADER=\"${name}_model.hpp\""
                                                     "NTN_MODEL_NS=ntn::models::${name}")
  endif()
endfunction()
