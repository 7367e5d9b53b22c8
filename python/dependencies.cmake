# Whether the Python module can be built: Python 3 with its headers, and
# pybind11. Debian's interpreter by default: it has numpy and pytest, which
# a pyenv python3 found first on PATH may lack.
if(EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter the module is built for")
endif()
# Python3 before pybind11, so that pybind11 builds for this interpreter.
find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
find_package(pybind11 CONFIG QUIET)
if(Python3_FOUND AND pybind11_FOUND)
  set(MR_PYTHON_FOUND ON)
else()
  set(MR_PYTHON_FOUND OFF)
endif()
