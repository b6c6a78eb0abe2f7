# Compiles GLSL stage files to SPIR-V with glslangValidator at build time. Includes are tracked
# through glslang's depfiles, so editing a header in shaders/shared/ rebuilds every stage using it.
function(wisp_compile_shaders target)
  cmake_parse_arguments(ARG "" "OUTPUT_DIR" "SOURCES" ${ARGN})
  set(outputs)
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(name ${src} NAME)
    set(spv ${ARG_OUTPUT_DIR}/${name}.spv)
    add_custom_command(
      OUTPUT ${spv}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${ARG_OUTPUT_DIR}
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.3 -g
              -I${CMAKE_SOURCE_DIR}/shaders
              --depfile ${spv}.d -o ${spv} ${CMAKE_SOURCE_DIR}/${src}
      DEPENDS ${CMAKE_SOURCE_DIR}/${src}
      DEPFILE ${spv}.d
      COMMENT "GLSL ${src}"
      VERBATIM)
    list(APPEND outputs ${spv})
  endforeach()
  add_custom_target(${target} ALL DEPENDS ${outputs})
endfunction()
