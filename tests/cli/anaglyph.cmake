# solrender --stereo anaglyph: the image is the eye's size; its red channel
# is the left eye's and its green and blue the right eye's of the
# side-by-side render of the same camera (float EXR, compared exactly).
#   -DSOLRENDER=path -DOIIOTOOL=path -DIDIFF=path -DWORK_DIR=dir
set(dir ${WORK_DIR}/anaglyph)
file(REMOVE_RECURSE ${dir})
file(MAKE_DIRECTORY ${dir})
foreach(mode side-by-side anaglyph)
  execute_process(COMMAND ${SOLRENDER} --scene lattice-balls --stereo ${mode} --ipd 0.2 --width 24 --height 16
      --device vulkan -o ${dir}/${mode}.exr
    RESULT_VARIABLE status ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "--stereo ${mode} failed: ${err}")
  endif()
endforeach()
if(NOT err MATCHES "24x16 \\(anaglyph\\)")
  message(FATAL_ERROR "the anaglyph is not the eye's size: ${err}")
endif()
execute_process(COMMAND ${OIIOTOOL} ${dir}/side-by-side.exr --cut 24x16+0+0 --ch R -o ${dir}/left-r.exr)
execute_process(COMMAND ${OIIOTOOL} ${dir}/side-by-side.exr --cut 24x16+24+0 --ch G,B -o ${dir}/right-gb.exr)
execute_process(COMMAND ${OIIOTOOL} ${dir}/anaglyph.exr --ch R -o ${dir}/ana-r.exr)
execute_process(COMMAND ${OIIOTOOL} ${dir}/anaglyph.exr --ch G,B -o ${dir}/ana-gb.exr)
foreach(pair "left-r;ana-r" "right-gb;ana-gb")
  list(GET pair 0 a)
  list(GET pair 1 b)
  execute_process(COMMAND ${IDIFF} -fail 0 ${dir}/${a}.exr ${dir}/${b}.exr RESULT_VARIABLE same OUTPUT_VARIABLE out)
  if(NOT same EQUAL 0)
    message(FATAL_ERROR "${a} and ${b} differ:\n${out}")
  endif()
endforeach()
