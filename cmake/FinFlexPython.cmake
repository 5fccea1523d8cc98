# Finds what the Python module (bindings/python) needs: the Python interpreter with its
# development files, and nanobind. Sets FINFLEX_PYTHON_FOUND.
#
# Without Python_EXECUTABLE given (scikit-build-core gives it), the interpreter is the
# `python3` on PATH: the one scripts/install-deps.sh installs nanobind, numpy and
# pytest for.
if(NOT DEFINED Python_EXECUTABLE)
  find_program(FINFLEX_PYTHON3 python3)
  if(FINFLEX_PYTHON3)
    execute_process(COMMAND ${FINFLEX_PYTHON3} -c "import sys; print(sys.executable)"
      OUTPUT_VARIABLE _finflex_python OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE _result)
    if(_result EQUAL 0 AND EXISTS "${_finflex_python}")
      set(Python_EXECUTABLE "${_finflex_python}" CACHE FILEPATH "Python interpreter")
    endif()
  endif()
endif()

set(FINFLEX_PYTHON_FOUND OFF)
find_package(Python 3.8 COMPONENTS Interpreter Development.Module QUIET)
if(Python_FOUND)
  execute_process(COMMAND ${Python_EXECUTABLE} -m nanobind --cmake_dir
    OUTPUT_VARIABLE _nanobind_dir OUTPUT_STRIP_TRAILING_WHITESPACE
    RESULT_VARIABLE _result ERROR_QUIET)
  if(_result EQUAL 0)
    list(APPEND CMAKE_PREFIX_PATH "${_nanobind_dir}")
    find_package(nanobind CONFIG QUIET)
    if(nanobind_FOUND)
      set(FINFLEX_PYTHON_FOUND ON)
    endif()
  endif()
endif()
