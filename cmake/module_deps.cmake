# module_deps.cmake: writes OUT, the shared libraries MODULE loads (ldd), one path a line,
# in the reverse of the loader's breadth-first order, so that the leaves come first.
# image_load.c loads them one by one before the module; host/image/image_load.c says why.
# Run by the build after each link of the module: cmake -DMODULE=... -DOUT=... -P this.
execute_process(COMMAND ldd ${MODULE} OUTPUT_VARIABLE listing RESULT_VARIABLE status ERROR_QUIET)
set(paths)
if(status EQUAL 0)
  string(REGEX MATCHALL "=> (/[^ \n]+)" found "${listing}")
  foreach(entry IN LISTS found)
    string(REGEX REPLACE "^=> " "" path "${entry}")
    list(PREPEND paths "${path}")
  endforeach()
endif()
# Written whole or not at all: a torn list would only lose speed, but a file is either the
# build's or absent.
list(JOIN paths "\n" text)
file(WRITE "${OUT}.tmp" "${text}\n")
file(RENAME "${OUT}.tmp" "${OUT}")
