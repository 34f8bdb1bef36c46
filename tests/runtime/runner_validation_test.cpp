// The validation messenger really reports: a deliberately broken stage interface (the
// fragment shader reads a varying the vertex shader never writes) must produce at least
// one message. Without this, "zero validation messages" in the other tests proves nothing.
#include "runner_support.h"

#include <catch2/catch.hpp>

using namespace watergen;

TEST_CASE("validation layer messages are collected", "[render][validation]") {
    // Its own runner: the shared one must stay free of messages.
    std::string error;
    auto runner = VulkanRunner::create(DeviceOptions{}, &error);
    INFO(error);
    REQUIRE(runner);
    REQUIRE(runner->device_info().validation_enabled);
    CHECK(runner->validation_messages().empty());

    RenderJob job = test::fullscreen_job(R"(#version 450
layout(location = 3) in vec4 never_written;
layout(location = 0) out vec4 color;
void main() { color = never_written; }
)",
                                         4, 4);
    job.timed_draws = 0;
    RenderResult r = runner->render(job);
    const auto messages = runner->validation_messages();
    INFO(test::joined(messages));
    CHECK_FALSE(messages.empty());
    runner->clear_validation_messages();
    CHECK(runner->validation_messages().empty());
}
