// Sol::vk, the Vulkan compute host library: everything at once.
#pragma once

#include "sol/vk/buffer.hpp"
#include "sol/vk/context.hpp"
#include "sol/vk/error.hpp"
#include "sol/vk/image.hpp"
#include "sol/vk/pipeline.hpp"
#include "sol/vk/shaders.hpp"
