#pragma once
#include <string>
#include <vulkan/vulkan.h>

namespace mixtrace {

// Turns a failed Vulkan call into a one-line mixtrace::Error naming the call and the result.
void vkCheck(VkResult result, const char* what);
const char* vkResultName(VkResult result);

}  // namespace mixtrace
