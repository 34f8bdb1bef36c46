// One Vulkan runner (lavapipe, validation on) per test binary.
#pragma once

#include <catch2/catch.hpp>

#include "watergen/runtime/vulkan_runner.h"

namespace watergen::test {

inline VulkanRunner& shared_runner() {
    static std::unique_ptr<VulkanRunner> r = [] {
        std::string error;
        auto created = VulkanRunner::create({}, &error);
        if (!created) FAIL("no Vulkan device: " << error);
        return created;
    }();
    return *r;
}

} // namespace watergen::test
