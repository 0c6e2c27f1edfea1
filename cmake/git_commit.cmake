# Sets VRSPH_GIT_COMMIT to the commit of the source tree (`git rev-parse HEAD`), or "unknown" when
# the source is not the top of a git checkout (an unpacked archive, or a folder inside someone
# else's repository) or git is missing. Nothing is fetched. The files git moves on a commit or a
# checkout (HEAD and the branch's ref) become configure dependencies, so the build notices a new
# commit and regenerates build_info.cpp (one file recompiled).
set(VRSPH_GIT_COMMIT "unknown")
find_package(Git QUIET)
if(GIT_FOUND)
  execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --show-toplevel HEAD
                  WORKING_DIRECTORY ${CMAKE_SOURCE_DIR} RESULT_VARIABLE _vrsph_git_rc
                  OUTPUT_VARIABLE _vrsph_git_out ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
  string(REPLACE "\n" ";" _vrsph_git_out "${_vrsph_git_out}")
  list(LENGTH _vrsph_git_out _vrsph_git_n)
  if(_vrsph_git_rc EQUAL 0 AND _vrsph_git_n EQUAL 2)
    list(GET _vrsph_git_out 0 _vrsph_git_top)
    list(GET _vrsph_git_out 1 _vrsph_git_head)
    file(REAL_PATH "${_vrsph_git_top}" _vrsph_git_top)
    file(REAL_PATH "${CMAKE_SOURCE_DIR}" _vrsph_source)
    if(_vrsph_git_top STREQUAL _vrsph_source)
      set(VRSPH_GIT_COMMIT "${_vrsph_git_head}")
      execute_process(COMMAND ${GIT_EXECUTABLE} symbolic-ref -q HEAD
                      WORKING_DIRECTORY ${CMAKE_SOURCE_DIR} OUTPUT_VARIABLE _vrsph_git_ref
                      ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
      set(_vrsph_git_watch HEAD)
      if(_vrsph_git_ref)
        list(APPEND _vrsph_git_watch ${_vrsph_git_ref})
      endif()
      foreach(_vrsph_f IN LISTS _vrsph_git_watch)
        execute_process(COMMAND ${GIT_EXECUTABLE} rev-parse --git-path ${_vrsph_f}
                        WORKING_DIRECTORY ${CMAKE_SOURCE_DIR} OUTPUT_VARIABLE _vrsph_p
                        ERROR_QUIET OUTPUT_STRIP_TRAILING_WHITESPACE)
        file(REAL_PATH "${_vrsph_p}" _vrsph_p BASE_DIRECTORY ${CMAKE_SOURCE_DIR})
        if(EXISTS "${_vrsph_p}")
          set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${_vrsph_p}")
        endif()
      endforeach()
    endif()
  endif()
endif()
