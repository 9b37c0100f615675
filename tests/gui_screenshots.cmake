# Smoke run of the real studio for ctest (gui_screenshots): `terrastudio gui --screenshots OUT`
# with HOME and the XDG directories pointing into a fresh temporary directory, so the studio's
# settings (QSettings), recent files and autosave never land in the user's configuration or in the
# source or build tree. The screenshots in OUT are the only output; the temporary directory (its
# file list is printed) is removed afterwards.
#   cmake -DEXE=<terrastudio> -DOUT=<dir> -P gui_screenshots.cmake
if(NOT EXE OR NOT OUT)
  message(FATAL_ERROR "usage: cmake -DEXE=<terrastudio> -DOUT=<dir> -P gui_screenshots.cmake")
endif()
set(tmp "$ENV{TMPDIR}")
if(NOT tmp)
  set(tmp "/tmp")
endif()
string(RANDOM LENGTH 10 suffix)
set(home "${tmp}/terrastudio-gui-screenshots-${suffix}")
file(MAKE_DIRECTORY "${home}")
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env
    QT_QPA_PLATFORM=offscreen HOME=${home}
    XDG_CONFIG_HOME=${home}/config XDG_DATA_HOME=${home}/data
    XDG_CACHE_HOME=${home}/cache XDG_STATE_HOME=${home}/state
    "${EXE}" gui --screenshots "${OUT}"
  RESULT_VARIABLE rc)
file(GLOB_RECURSE written RELATIVE "${home}" "${home}/*")
list(LENGTH written count)
message(STATUS "settings and autosave went to the temporary ${home}: ${count} file(s) ${written}")
file(REMOVE_RECURSE "${home}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "terrastudio gui --screenshots exited with ${rc}")
endif()
