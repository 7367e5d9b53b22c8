# Finds OpenVDB for the directory that includes this file. Include it, do not
# call it from the top level: FindOpenVDB sets BUILD_SHARED_LIBS in the scope
# it runs in.
# Debian's OpenVDB is built with delayed loading, so FindOpenVDB requires
# Boost::iostreams, whose CMake files only libboost-iostreams-dev installs.
find_package(Boost QUIET COMPONENTS iostreams)
if(NOT Boost_IOSTREAMS_FOUND)
  message(FATAL_ERROR "OpenVDB needs libboost-iostreams-dev (apt-get install libboost-iostreams-dev), "
                      "or configure with -DMR_WITH_VDB=OFF")
endif()
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)
