# Packages one scene into an FMU (a zip):
#   modelDescription.xml, binaries/linux64/<modelIdentifier>.so, resources/scene.json
# cmake -DSCENE=scene.json -DOUT=out.fmu -DDESCRIBE=rigidfmu-describe -DLIBRARY=lib.so -P package_fmu.cmake
foreach(arg SCENE OUT DESCRIBE LIBRARY)
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
file(REMOVE "${stage}/model_identifier")

file(COPY_FILE "${LIBRARY}" "${stage}/binaries/linux64/${model_identifier}.so")
file(COPY_FILE "${SCENE}" "${stage}/resources/scene.json")

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
message(STATUS "FMU ${model_identifier}: ${out_abs}")
