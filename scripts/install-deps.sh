#!/usr/bin/env bash
# Installs the Debian 12 packages Sol needs to build and test. Idempotent.
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config
  clang libclang-rt-dev  # the sanitizer build and its libFuzzer targets (tests/fuzz/)
  libglm-dev            # vectors and matrices
  libboost-dev          # header-only Boost.Math / Odeint / Multiprecision: independent test references
  libgtest-dev libgmock-dev googletest
  libbenchmark-dev
  nlohmann-json3-dev    # scene files
  libcli11-dev          # the programs' command lines
  libopenimageio-dev openimageio-tools  # image files (OIIO's CMake config also checks for its tools)
  python3-matplotlib    # bench plots
  libvulkan-dev         # Vulkan headers and loader (Sol::vk)
  mesa-vulkan-drivers   # lavapipe: the CPU Vulkan device the tests run on
  glslang-tools         # glslangValidator: GLSL compute shaders to SPIR-V at build time
  spirv-tools           # SPIRV-Tools: Sol::vk validates SPIR-V and folds its specialisation constants before a driver sees it
  vulkan-validationlayers  # VK_LAYER_KHRONOS_validation, on in the Vulkan tests
  libopenxr-dev libopenxr-loader1  # OpenXR headers and loader: solxr and its headless test runtime
  openxr-layer-corevalidation  # tests: every solxr run under the OpenXR core validation layer
  libglfw3-dev          # solview: window and Vulkan surface
  libimgui-dev          # solview: its overlay panel (Dear ImGui; the GLFW and Vulkan backends are compiled in)
  xvfb xauth            # solview's tests: a virtual X display (xvfb-run)
  parallel              # the film test: frames shard over GNU parallel jobs (docs/films.md)
  ffmpeg                # solrender --video (films) and its test
  pybind11-dev python3-dev python3-numpy python3-pytest  # the Python module sol and its tests
  python3-nbclient python3-ipykernel  # tests: docs/notebooks/tour.ipynb executed headless
  libassimp-dev         # solshape: meshes to PLY, OBJ and STL
  admesh                # tests: solshape's STL files checked by a third-party mesh checker
  libcgal-dev           # tests: geodesic sphere meshes checked for self-intersection (CGAL, exact predicates)
)
if [ "$(id -u)" -eq 0 ]; then sudo=(); else sudo=(sudo); fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "install-deps: all packages present"
fi
