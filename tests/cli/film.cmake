# solrender --path: a film of a camera path. Renders frames 0..2, then the
# whole path (the first three are skipped: the run resumes); every frame is
# there; frame 2 equals a still render from the camera the path puts there.
# The path walks straight down from (0, 0, 1.5) looking down (-z): that
# geodesic is the vertical line, so frame k at t = k/4 s is at z = 1.5 - k/4.
#   -DSOLRENDER=path -DIDIFF=path -DWORK_DIR=dir
if(NOT IDIFF)
  message(FATAL_ERROR "idiff not found (Debian: openimageio-tools)")
endif()
set(dir ${WORK_DIR}/film)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
file(WRITE ${dir}/down.json "{\"segments\": [{\"walk\": \"forward\", \"distance\": 1, \"duration\": 1}, {\"hold\": 0.25}]}")
set(common --scene plane --path ${dir}/down.json --fps 4 --width 48 --height 32 -o ${dir}/frame-%03d.png)
execute_process(COMMAND ${SOLRENDER} ${common} --frames 0:3 RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT err MATCHES "frames 0\\.\\.2 at 4 fps .*: 3 rendered in [0-9.]+ s, 0 already there")
  message(FATAL_ERROR "first part of the film (${status}):\n${err}")
endif()
execute_process(COMMAND ${SOLRENDER} ${common} RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0 OR NOT err MATCHES "frames 0\\.\\.5 at 4 fps .*: 3 rendered in [0-9.]+ s, 3 already there")
  message(FATAL_ERROR "the resumed film (${status}):\n${err}")
endif()
foreach(k 000 001 002 003 004 005)
  if(NOT EXISTS ${dir}/frame-${k}.png)
    message(FATAL_ERROR "frame ${k} is missing")
  endif()
endforeach()
execute_process(COMMAND ${SOLRENDER} --scene plane --width 48 --height 32 --position 0,0,1 --forward 0,0,-1 --up 0,1,0
  -o ${dir}/still.png RESULT_VARIABLE status ERROR_VARIABLE err)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "the still render failed: ${err}")
endif()
# The same kernel and the same camera up to the observer's double rounding:
# as solview's screenshot test, at most 1% of the pixels beyond one 8-bit step.
execute_process(COMMAND ${IDIFF} -fail 0.005 -failpercent 1 ${dir}/frame-002.png ${dir}/still.png
  RESULT_VARIABLE status OUTPUT_VARIABLE out)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "frame 2 (t = 0.5 s, z = 1) differs from the still at z = 1:\n${out}")
endif()
# And differs from frame 0 (z = 1.5): the camera moved.
execute_process(COMMAND ${IDIFF} -fail 0.005 -failpercent 1 ${dir}/frame-000.png ${dir}/still.png
  RESULT_VARIABLE status OUTPUT_VARIABLE out)
if(status EQUAL 0)
  message(FATAL_ERROR "frame 0 equals the still at z = 1: the path did not move the camera")
endif()
