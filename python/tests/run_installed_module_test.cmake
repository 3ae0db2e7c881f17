# Installs the python component of BUILD_DIR into PREFIX and imports sinew from PREFIX/SITE_DIR only (run
# from PREFIX: `python -c` puts its working folder first on sys.path, and the build tree's module sits there).
file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX} --component python
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "installing the python component failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=PYTHONPATH PYTHONPATH=${PREFIX}/${SITE_DIR}
                        ${PYTHON} -c "import sinew, sys; assert sinew.__file__.startswith('${PREFIX}'), sinew.__file__; print(sinew.__file__)"
                WORKING_DIRECTORY ${PREFIX} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "import sinew from ${PREFIX}/${SITE_DIR} failed (${rc})")
endif()
