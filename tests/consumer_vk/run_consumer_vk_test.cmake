# Installs the built Sol into a scratch prefix, configures, builds and runs
# tests/consumer_vk against it (headless, and in an application's own
# device), renders the same frame with the build's solrender, and compares
# them (cmake -P script, run by ctest):
#   -DSOL_BUILD_DIR -DCONSUMER_SOURCE_DIR -DWORK_DIR -DGENERATOR -DSOLRENDER -DOIIOTOOL -DIDIFF
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(rc)
    message(FATAL_ERROR "${what} failed: ${rc}")
  endif()
endfunction()
run("cmake --install" ${CMAKE_COMMAND} --install ${SOL_BUILD_DIR} --prefix ${prefix})
run("configuring the consumer project" ${CMAKE_COMMAND} -S ${CONSUMER_SOURCE_DIR} -B ${WORK_DIR}/build -G ${GENERATOR}
    -DCMAKE_PREFIX_PATH=${prefix})
run("building the consumer project" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run("the consumer program" ${WORK_DIR}/build/consumer_vk sandwich 48 36 ${WORK_DIR}/consumer.pfm ${WORK_DIR}/app.ppm)
run("solrender" ${SOLRENDER} --scene sandwich --width 48 --height 36 --device vulkan -o ${WORK_DIR}/solrender.exr)
run("solrender" ${SOLRENDER} --scene sandwich --width 48 --height 36 --device vulkan -o ${WORK_DIR}/solrender.png)
run("oiiotool" ${OIIOTOOL} ${WORK_DIR}/solrender.exr --ch R,G,B -o ${WORK_DIR}/solrender-rgb.exr)
# The same kernel on the same device from the same world and camera: the
# same floats (idiff's default threshold, 1e-6).
run("comparing the consumer's frame with solrender's" ${IDIFF} ${WORK_DIR}/consumer.pfm ${WORK_DIR}/solrender-rgb.exr)
# The application's frame (its device, command buffer and 8-bit image): the
# kernel's own sRGB encoding of the same colour, which is within 1 in 255 of
# solrender's rounding of it (MarchRenderer::record's UnormTarget), so the
# threshold is 1/255 and a little.
run("oiiotool" ${OIIOTOOL} ${WORK_DIR}/solrender.png --ch R,G,B -o ${WORK_DIR}/solrender-rgb.png)
run("comparing the application's frame with solrender's" ${IDIFF} -fail 0.0040 -warn 0.0040 ${WORK_DIR}/app.ppm ${WORK_DIR}/solrender-rgb.png)
