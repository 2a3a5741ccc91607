# The overlay panel changes the screenshot only where the panel is: runs
# solview twice with the same options, --overlay off and --overlay on (which
# takes the panel into screenshots), reads where the panel was from the
# second run's stderr, paints that rectangle black in both screenshots
# (oiiotool) and requires the rest to be identical (idiff, no tolerance:
# the same kernel renders the same frame, the panel is drawn after it);
# and requires the two screenshots to differ (the panel was drawn).
#   -DSOLVIEW=path -DARGS="a;b" -DWORK_DIR=dir -DXVFB_RUN=path -DOIIOTOOL=path -DIDIFF=path -DNAME=prefix
file(MAKE_DIRECTORY ${WORK_DIR})
set(launcher ${XVFB_RUN} -a -s "-screen 0 1024x768x24")
set(off ${WORK_DIR}/${NAME}-off.png)
set(on ${WORK_DIR}/${NAME}-on.png)
file(REMOVE ${off} ${on})
execute_process(COMMAND ${launcher} ${SOLVIEW} ${ARGS} --overlay off --screenshot ${off} WORKING_DIRECTORY ${WORK_DIR}
  RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 120)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "solview --overlay off failed (${status}): ${err}")
endif()
if(err MATCHES "overlay panel at")
  message(FATAL_ERROR "solview --overlay off drew the panel:\n${err}")
endif()
execute_process(COMMAND ${launcher} ${SOLVIEW} ${ARGS} --overlay on --screenshot ${on} WORKING_DIRECTORY ${WORK_DIR}
  RESULT_VARIABLE status ERROR_VARIABLE err TIMEOUT 120)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "solview --overlay on failed (${status}): ${err}")
endif()
if(err MATCHES "validation|VUID")
  message(FATAL_ERROR "solview --overlay on: validation messages:\n${err}")
endif()
if(NOT err MATCHES "overlay panel at ([0-9]+),([0-9]+) size ([0-9]+)x([0-9]+)")
  message(FATAL_ERROR "solview --overlay on did not report the panel:\n${err}")
endif()
# One pixel of margin around the rectangle: its border is anti-aliased.
math(EXPR x "${CMAKE_MATCH_1} - 1")
math(EXPR y "${CMAKE_MATCH_2} - 1")
math(EXPR w "${CMAKE_MATCH_3} + 2")
math(EXPR h "${CMAKE_MATCH_4} + 2")
if(x LESS 0)
  set(x 0)
endif()
if(y LESS 0)
  set(y 0)
endif()
execute_process(COMMAND ${IDIFF} ${off} ${on} RESULT_VARIABLE status OUTPUT_VARIABLE dout)
if(status EQUAL 0)
  message(FATAL_ERROR "the screenshots with and without the panel are the same: it was not drawn")
endif()
foreach(which off on)
  execute_process(COMMAND ${OIIOTOOL} ${${which}} --fill:color=0,0,0,1 ${w}x${h}+${x}+${y} -o ${WORK_DIR}/${NAME}-${which}-masked.png
    RESULT_VARIABLE status ERROR_VARIABLE oerr)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "oiiotool failed: ${oerr}")
  endif()
endforeach()
execute_process(COMMAND ${IDIFF} -fail 0 ${WORK_DIR}/${NAME}-off-masked.png ${WORK_DIR}/${NAME}-on-masked.png
  RESULT_VARIABLE status OUTPUT_VARIABLE dout ERROR_VARIABLE derr)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "outside the panel (${w}x${h}+${x}+${y}) the screenshots differ:\n${dout}${derr}")
endif()
