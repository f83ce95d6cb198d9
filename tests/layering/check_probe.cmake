# Builds one layering probe (tests/layering/CMakeLists.txt) and checks the outcome.
# -DBUILD_DIR= -DSOURCE_DIR= -DTARGET= -DEXPECT=fail|pass -DHEADERS=<h1>,<h2>,...
cmake_minimum_required(VERSION 3.24)
string(REPLACE "," ";" headers "${HEADERS}")
foreach(header IN LISTS headers)
  # A moved header would make a "fail" probe pass for the wrong reason.
  if(NOT EXISTS ${SOURCE_DIR}/${header})
    message(FATAL_ERROR "probe header ${header} is not in the source tree: update "
                        "tests/layering/CMakeLists.txt")
  endif()
endforeach()

execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGET}
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)

if(EXPECT STREQUAL "pass")
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${TARGET} should build (allowed includes), but:\n${output}")
  endif()
  message(STATUS "${TARGET} builds: ${HEADERS} visible")
  return()
endif()

list(GET headers 0 header)
string(REGEX REPLACE "([.+])" "\\\\\\1" pattern "${header}")
if(status EQUAL 0)
  message(FATAL_ERROR "${TARGET} built: ${header} is visible where the layering forbids it")
endif()
# GCC: "<header>: No such file or directory"; Clang: "'<header>' file not found".
if(NOT output MATCHES "${pattern}: No such file or directory|'${pattern}' file not found")
  message(FATAL_ERROR "${TARGET} failed, but not for want of ${header}:\n${output}")
endif()
message(STATUS "${TARGET} fails as it should: ${header} not found")
