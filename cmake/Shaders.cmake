# Compiles GLSL stage files to SPIR-V with glslangValidator at build time. Includes are tracked
# through glslang's depfiles, so editing a header in shaders/shared/ rebuilds every stage using it.
#   SOURCES  shaders/x.comp ...                      -> x.comp.spv
#   VARIANTS shaders/x.comp SUFFIX DEFINE ...        -> x_SUFFIX.comp.spv, compiled with -DDEFINE
# (variants are separate SPIR-V where they need different device capabilities).
function(wisp_compile_shaders target)
  cmake_parse_arguments(ARG "" "OUTPUT_DIR" "SOURCES;VARIANTS" ${ARGN})
  set(outputs)
  set(jobs)
  foreach(src IN LISTS ARG_SOURCES)
    get_filename_component(name ${src} NAME)
    list(APPEND jobs "${src}|${name}|")
  endforeach()
  list(LENGTH ARG_VARIANTS count)
  if(count GREATER 0)
    math(EXPR last "${count} - 1")
    foreach(i RANGE 0 ${last} 3)
      math(EXPR j "${i} + 1")
      math(EXPR k "${i} + 2")
      list(GET ARG_VARIANTS ${i} src)
      list(GET ARG_VARIANTS ${j} suffix)
      list(GET ARG_VARIANTS ${k} define)
      get_filename_component(stem ${src} NAME_WE)
      get_filename_component(ext ${src} LAST_EXT)
      list(APPEND jobs "${src}|${stem}_${suffix}${ext}|-D${define}")
    endforeach()
  endif()
  foreach(job IN LISTS jobs)
    string(REPLACE "|" ";" parts "${job}")
    list(GET parts 0 src)
    list(GET parts 1 name)
    list(LENGTH parts n)
    set(define "")
    if(n GREATER 2)
      list(GET parts 2 define)
    endif()
    set(spv ${ARG_OUTPUT_DIR}/${name}.spv)
    add_custom_command(
      OUTPUT ${spv}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${ARG_OUTPUT_DIR}
      COMMAND ${GLSLANG_VALIDATOR} --quiet --target-env vulkan1.3 -g ${define}
              -I${CMAKE_SOURCE_DIR}/shaders
              --depfile ${spv}.d -o ${spv} ${CMAKE_SOURCE_DIR}/${src}
      DEPENDS ${CMAKE_SOURCE_DIR}/${src}
      DEPFILE ${spv}.d
      COMMENT "GLSL ${name}"
      VERBATIM)
    list(APPEND outputs ${spv})
  endforeach()
  add_custom_target(${target} ALL DEPENDS ${outputs})
endfunction()
