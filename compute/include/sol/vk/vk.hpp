// Sol::vk, the Vulkan compute host library: everything at once (the device,
// buffers, images, pipelines, shaders, the ray-marcher sol::vk::MarchRenderer
// and its interface with the kernel; the kernel's test probes,
// sol/vk/kernel_probes.hpp, stay out).
#pragma once

#include "sol/vk/buffer.hpp"
#include "sol/vk/context.hpp"
#include "sol/vk/display.hpp"
#include "sol/vk/error.hpp"
#include "sol/vk/frame_timer.hpp"
#include "sol/vk/image.hpp"
#include "sol/vk/march.hpp"
#include "sol/vk/march_interface.h"
#include "sol/vk/pipeline.hpp"
#include "sol/vk/shaders.hpp"
