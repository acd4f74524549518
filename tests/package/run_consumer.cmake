# Installs the built library into a scratch prefix, then configures, builds and runs a separate
# project that finds it with find_package(facesocial).
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build
                -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the consumer failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the consumer failed: ${rc}")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer RESULT_VARIABLE rc OUTPUT_VARIABLE out)
message(STATUS "consumer said: ${out}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "facesocial [0-9]+\\.[0-9]+\\.[0-9]+ ok")
  message(FATAL_ERROR "consumer failed: ${rc} ${out}")
endif()

# The Python package installed by the same `cmake --install` imports from the prefix.
if(PYTHON_EXECUTABLE AND PYTHON_INSTALL_DIR)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${PYTHON_INSTALL_DIR}
                  ${PYTHON_EXECUTABLE} -c "import facesocial; print('python', facesocial.__version__, facesocial.EhmmParams().mixtures)"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "python said: ${out}")
  if(NOT rc EQUAL 0 OR NOT out MATCHES "python [0-9]+\\.[0-9]+\\.[0-9]+ 3")
    message(FATAL_ERROR "importing the installed Python package failed: ${rc} ${out} ${err}")
  endif()
endif()
