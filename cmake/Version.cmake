# Records the software version and the git commit the build came from, so that
# `dtlab --version` and every study database name the code that produced them.
# The commit is read at configure time; "-dirty" marks uncommitted changes.
find_package(Git QUIET)
set(DTLAB_GIT_COMMIT "unknown")
if(GIT_FOUND AND EXISTS "${CMAKE_SOURCE_DIR}/.git")
  execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --short=12 HEAD
                  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
                  OUTPUT_VARIABLE _commit OUTPUT_STRIP_TRAILING_WHITESPACE
                  RESULT_VARIABLE _rc ERROR_QUIET)
  if(_rc EQUAL 0)
    set(DTLAB_GIT_COMMIT "${_commit}")
    execute_process(COMMAND ${GIT_EXECUTABLE} status --porcelain --untracked-files=no
                    WORKING_DIRECTORY ${CMAKE_SOURCE_DIR}
                    OUTPUT_VARIABLE _dirty OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(_dirty)
      set(DTLAB_GIT_COMMIT "${DTLAB_GIT_COMMIT}-dirty")
    endif()
  endif()
endif()
configure_file(${CMAKE_SOURCE_DIR}/study/common/version.cpp.in
               ${CMAKE_BINARY_DIR}/generated/version.cpp @ONLY)
