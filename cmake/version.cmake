# Writes OUT (a header with VKRAYCAST_GIT_REVISION) at every build, touching it only when
# the revision changed, so that `vkraycast --version` names the commit it was built from
# without rebuilding anything else. Outside a git checkout (a release tarball) the
# revision is empty. Run by the vkraycast_version target (CMakeLists.txt).
execute_process(COMMAND git -C "${SRC}" describe --always --dirty --abbrev=12
                OUTPUT_VARIABLE rev OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE failed)
if(failed)
  set(rev "")
endif()
set(text "#define VKRAYCAST_GIT_REVISION \"${rev}\"\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
