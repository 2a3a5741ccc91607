# Runs solview (under Xvfb, or with no display at all) and checks its exit
# status, its stderr and the files it left; optionally compares its
# screenshot with solrender's image for the camera solview ended at.
#   -DSOLVIEW=path -DARGS="a;b" -DWORK_DIR=dir -DXVFB_RUN=path (empty: no Xvfb)
#   -DNO_DISPLAY=ON: run with DISPLAY and WAYLAND_DISPLAY unset
#   -DEXPECT_FAIL=ON|OFF -DEXPECT_STDERR=regex -DFORBID_STDERR=regex
#   -DMUST_EXIST="f1;f2" -DMUST_NOT_EXIST="f1;f2"
#   -DCOMPARE_SOLRENDER=path -DSCREENSHOT=png -DSTATE=file -DSCENE=name -DSIZE=WxH -DIDIFF=path
#   -DRENDER_ARGS="a;b": more solrender options for the comparison (what a script set in solview)
#   -DEXPECT_STDOUT=regex -DSAME_FILES="a.png;b.png": two images that must be identical (idiff)
file(MAKE_DIRECTORY ${WORK_DIR})
foreach(f IN LISTS MUST_NOT_EXIST MUST_EXIST SCREENSHOT STATE)
  file(REMOVE ${f})
endforeach()
if(NO_DISPLAY)
  set(launcher ${CMAKE_COMMAND} -E env --unset=DISPLAY --unset=WAYLAND_DISPLAY)
elseif(XVFB_RUN)
  # -a: a free display number; a 24-bit screen so that sRGB formats are offered.
  set(launcher ${XVFB_RUN} -a -s "-screen 0 1024x768x24")
else()
  message(FATAL_ERROR "xvfb-run not found (Debian: xvfb, xauth)")
endif()
execute_process(COMMAND ${launcher} ${SOLVIEW} ${ARGS} WORKING_DIRECTORY ${WORK_DIR}
  RESULT_VARIABLE status ERROR_VARIABLE err OUTPUT_VARIABLE out TIMEOUT 120)
if(EXPECT_FAIL AND status EQUAL 0)
  message(FATAL_ERROR "solview ${ARGS} succeeded but should fail\nstderr: ${err}")
endif()
if(NOT EXPECT_FAIL AND NOT status EQUAL 0)
  message(FATAL_ERROR "solview ${ARGS} failed (${status})\nstdout: ${out}\nstderr: ${err}")
endif()
if(DEFINED EXPECT_STDERR AND NOT err MATCHES "${EXPECT_STDERR}")
  message(FATAL_ERROR "stderr of solview ${ARGS} does not match '${EXPECT_STDERR}':\n${err}")
endif()
if(EXPECT_STDOUT AND NOT out MATCHES "${EXPECT_STDOUT}")
  message(FATAL_ERROR "stdout of solview ${ARGS} does not match '${EXPECT_STDOUT}':\n${out}")
endif()
if(SAME_FILES)
  execute_process(COMMAND ${IDIFF} -fail 0 ${SAME_FILES} RESULT_VARIABLE same OUTPUT_VARIABLE dout ERROR_VARIABLE derr)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "${SAME_FILES} differ:\n${dout}${derr}")
  endif()
endif()
if(FORBID_STDERR AND err MATCHES "${FORBID_STDERR}")
  message(FATAL_ERROR "stderr of solview ${ARGS} matches '${FORBID_STDERR}':\n${err}")
endif()
foreach(f IN LISTS MUST_NOT_EXIST)
  if(EXISTS ${f})
    message(FATAL_ERROR "solview ${ARGS} left ${f} behind")
  endif()
endforeach()
foreach(f IN LISTS MUST_EXIST)
  if(NOT EXISTS ${f})
    message(FATAL_ERROR "solview ${ARGS} did not write ${f}")
  endif()
endforeach()

if(COMPARE_SOLRENDER)
  # The camera solview ended at (its --state file, %.17g: exact doubles).
  file(STRINGS ${STATE} lines)
  foreach(line IN LISTS lines)
    if(line MATCHES "^(position|forward|up) ([^ ]+) ([^ ]+) ([^ ]+)$")
      set(${CMAKE_MATCH_1} "${CMAKE_MATCH_2},${CMAKE_MATCH_3},${CMAKE_MATCH_4}")
    endif()
  endforeach()
  string(REPLACE "x" ";" wh ${SIZE})
  list(GET wh 0 w)
  list(GET wh 1 h)
  set(reference ${WORK_DIR}/solrender-reference.png)
  file(REMOVE ${reference})
  execute_process(COMMAND ${COMPARE_SOLRENDER} --scene ${SCENE} --width ${w} --height ${h} --device vulkan
      --position ${position} --forward ${forward} --up ${up} ${RENDER_ARGS} -o ${reference}
    RESULT_VARIABLE status ERROR_VARIABLE rerr)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "solrender failed: ${rerr}")
  endif()
  # Tolerance: both images come from the same kernel and camera. solview's
  # screenshot is the swapchain image as shown: the blit's sRGB encoding (the
  # driver's) against solrender's (viewer/image_file.cpp), either of which may
  # round a value to the neighbouring 8-bit step. The viewer's observer
  # re-orthonormalises its frame in double after every step and hands the
  # kernel (forward, up) from that frame; solrender rebuilds the basis from
  # the same doubles, so a float ULP may differ in the basis. That moves a
  # colour by at most one 8-bit step (1/255 < 0.005) except where a ray
  # grazes an edge (a disc or a ball's rim) and flips from one side to the
  # other: allow 1% of the pixels to exceed 0.005, none to exceed 0.5 on
  # more than that share. A wrong camera, a flipped axis, a swapped channel
  # or a missing sRGB encoding changes far more than 1% of the pixels.
  execute_process(COMMAND ${IDIFF} -fail 0.005 -failpercent 1 -warn 0.005 -warnpercent 1 ${SCREENSHOT} ${reference}
    RESULT_VARIABLE status OUTPUT_VARIABLE dout ERROR_VARIABLE derr)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "solview's screenshot differs from solrender's image beyond the tolerance:\n${dout}${derr}")
  endif()
  message(STATUS "idiff: ${dout}")
endif()
message(STATUS "ok: ${err}")
