# Packages one scene into an FMU (a zip):
#   modelDescription.xml, binaries/linux64/<modelIdentifier>.so (+ the shared libraries
#   it needs beyond the C/C++ runtime, found through RUNPATH $ORIGIN), resources/scene.json
# cmake -DSCENE=scene.json -DOUT=out.fmu -DDESCRIBE=rigidfmu-describe -DLIBRARY_DIR=build
#       -P package_fmu.cmake
# The binary is the prebuilt rigidfmu_fmi2_<mask>.so with just the modules the scene
# needs (src/modules.h).
foreach(arg SCENE OUT DESCRIBE LIBRARY_DIR)
  if(NOT DEFINED ${arg})
    message(FATAL_ERROR "package_fmu.cmake: -D${arg}=... is required")
  endif()
endforeach()

get_filename_component(out_abs "${OUT}" ABSOLUTE)
set(stage "${out_abs}.staging")
file(REMOVE_RECURSE "${stage}")
file(MAKE_DIRECTORY "${stage}/binaries/linux64" "${stage}/resources")

# The describe tool checks the scene (its message names the field and the limit).
execute_process(COMMAND "${DESCRIBE}" "${SCENE}" "${stage}"
  RESULT_VARIABLE result ERROR_VARIABLE errors)
if(NOT result EQUAL 0)
  file(REMOVE_RECURSE "${stage}")
  message(FATAL_ERROR "scene refused: ${errors}")
endif()
file(READ "${stage}/model_identifier" model_identifier)
file(READ "${stage}/modules" modules)
string(STRIP "${modules}" modules)
file(REMOVE "${stage}/model_identifier" "${stage}/modules")

set(library "${LIBRARY_DIR}/rigidfmu_fmi2_${modules}.so")
if(NOT EXISTS "${library}")
  file(REMOVE_RECURSE "${stage}")
  message(FATAL_ERROR "no binary for modules ${modules}: ${library} (build target rigidfmu_fmus)")
endif()
set(binary "${stage}/binaries/linux64/${model_identifier}.so")
file(COPY_FILE "${library}" "${binary}")
file(COPY_FILE "${SCENE}" "${stage}/resources/scene.json")

# Self-contained: every shared library beyond the C and C++ runtime goes beside the
# binary, with RUNPATH $ORIGIN so that each finds the others there.
file(GET_RUNTIME_DEPENDENCIES
  LIBRARIES "${library}"
  RESOLVED_DEPENDENCIES_VAR dependencies
  UNRESOLVED_DEPENDENCIES_VAR unresolved
  POST_EXCLUDE_REGEXES
    ".*/ld-linux[^/]*$" ".*/libc\\.so[^/]*$" ".*/libm\\.so[^/]*$" ".*/libstdc\\+\\+\\.so[^/]*$"
    ".*/libgcc_s\\.so[^/]*$" ".*/libpthread\\.so[^/]*$" ".*/libdl\\.so[^/]*$" ".*/librt\\.so[^/]*$"
    # a sanitizer build's runtimes come from the host process (LD_PRELOAD), never the FMU
    ".*/libasan\\.so[^/]*$" ".*/libubsan\\.so[^/]*$")
if(unresolved)
  message(FATAL_ERROR "unresolved libraries of ${library}: ${unresolved}")
endif()
find_program(PATCHELF patchelf)
set(bundled "")
foreach(dependency ${dependencies})
  get_filename_component(name "${dependency}" NAME)
  file(COPY_FILE "${dependency}" "${stage}/binaries/linux64/${name}")
  list(APPEND bundled "${name}")
  if(NOT PATCHELF)
    message(FATAL_ERROR "patchelf is needed to bundle ${name} (scripts/setup.sh installs it)")
  endif()
  execute_process(COMMAND "${PATCHELF}" --set-rpath "$ORIGIN" "${stage}/binaries/linux64/${name}"
    RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "patchelf failed on ${name}")
  endif()
endforeach()

get_filename_component(out_dir "${out_abs}" DIRECTORY)
file(MAKE_DIRECTORY "${out_dir}")
file(REMOVE "${out_abs}")
execute_process(
  COMMAND ${CMAKE_COMMAND} -E tar cf "${out_abs}" --format=zip modelDescription.xml binaries resources
  WORKING_DIRECTORY "${stage}" RESULT_VARIABLE result)
file(REMOVE_RECURSE "${stage}")
if(NOT result EQUAL 0)
  message(FATAL_ERROR "could not write ${out_abs}")
endif()
message(STATUS "FMU ${model_identifier} (modules ${modules}; bundled: ${bundled}): ${out_abs}")
