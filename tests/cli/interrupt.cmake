# A long render interrupted by SIGINT (in the foreground, as a terminal's
# Ctrl-C: a background job would ignore it) stops within a second, exits
# non-zero and leaves nothing: neither the image nor a temporary beside it.
#   -DSOLRENDER=path -DWORK_DIR=dir -DTIMEOUT=path (coreutils' timeout)
file(MAKE_DIRECTORY ${WORK_DIR}/interrupt)
file(GLOB old ${WORK_DIR}/interrupt/* ${WORK_DIR}/interrupt/.*)
if(old)
  file(REMOVE ${old})
endif()
string(TIMESTAMP begin "%s")
# 2048 x 2048 of the lattice takes about 7 s on lavapipe (0.6 M rays/s) and
# much longer on the CPU: the signal comes 1 s in, mid-render.
execute_process(COMMAND ${TIMEOUT} --preserve-status -s INT -k 5 1 ${SOLRENDER} --scene lattice-balls --width 2048 --height 2048 --progress
    -o ${WORK_DIR}/interrupt/long.png
  RESULT_VARIABLE status ERROR_VARIABLE err)
string(TIMESTAMP end "%s")
math(EXPR seconds "${end} - ${begin}")
if(status EQUAL 0)
  message(FATAL_ERROR "the interrupted render exited 0:\n${err}")
endif()
if(status EQUAL 137)
  message(FATAL_ERROR "SIGINT did not stop the render (timeout had to kill it)")
endif()
if(seconds GREATER 4)
  message(FATAL_ERROR "the render took ${seconds} s to stop after SIGINT at 1 s")
endif()
file(GLOB left ${WORK_DIR}/interrupt/* ${WORK_DIR}/interrupt/.*)
if(left)
  message(FATAL_ERROR "the interrupted render left files: ${left}")
endif()
message(STATUS "interrupted: exit status ${status} after ${seconds} s, no files")
