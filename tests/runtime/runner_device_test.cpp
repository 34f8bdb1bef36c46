// Device selection: lavapipe by default, overrides by option and environment, and a clear
// error (not a crash) when nothing matches.
#include "runner_support.h"

#include <catch2/catch.hpp>

#include <vulkan/vulkan_core.h>

#include <cstdlib>
#include <optional>

using namespace watergen;

namespace {

// Sets an environment variable for one scope and restores the previous value.
class ScopedEnv {
  public:
    ScopedEnv(const char* name, const char* value) : name_(name) {
        if (const char* old = std::getenv(name)) old_ = old;
        setenv(name, value, 1);
    }
    ~ScopedEnv() {
        if (old_)
            setenv(name_, old_->c_str(), 1);
        else
            unsetenv(name_);
    }

  private:
    const char* name_;
    std::optional<std::string> old_;
};

} // namespace

TEST_CASE("runner picks lavapipe and reports it", "[render][device]") {
    VulkanRunner& runner = test::shared_runner();
    const DeviceInfo& info = runner.device_info();
    INFO("device " << info.name << ", driver " << info.driver_name << " " << info.driver_info
                   << ", api " << format_api_version(info.api_version));
    CHECK(info.name.find("llvmpipe") != std::string::npos);
    CHECK(info.driver_name == "llvmpipe");
    CHECK(info.driver_info.find("Mesa") != std::string::npos);
    CHECK(info.api_version >= VK_API_VERSION_1_1);
    CHECK(info.validation_enabled); // vulkan-validationlayers is a build dependency
    CHECK(runner.validation_messages().empty());
}

TEST_CASE("runner enables lavapipe's 16-bit shader features", "[render][device]") {
    // Mesa 22.3's lavapipe has float16 / int16 arithmetic and 16-bit storage-buffer access;
    // the runner enables what the device has, so float16_t shaders run without validation
    // errors (tests/render/float16_probe_test.cpp measures what that arithmetic does).
    const DeviceInfo& info = test::shared_runner().device_info();
    CHECK(info.shader_float16);
    CHECK(info.shader_int16);
    CHECK(info.storage_buffer_16bit);
    CHECK(info.uniform_storage_16bit);
    // Not asserted: Mesa 22.3 does not promise shaderDenormPreserveFloat16 (false), though
    // the probe's binary16 subnormals (2^-14 * 0.5, 1023 * 2^-24 * 0.5) do survive.
    INFO("shaderDenormPreserveFloat16 " << info.float16_denorms_preserved);
}

TEST_CASE("device overrides select by name substring or fail clearly", "[render][device]") {
    // Validation off: these runners only test selection, and skipping the layer keeps
    // each creation cheap.
    DeviceOptions options;
    options.validation = false;

    SECTION("option with no matching device") {
        options.device = "no-such-gpu";
        std::string error;
        auto runner = VulkanRunner::create(options, &error);
        CHECK_FALSE(runner);
        CHECK(error.find("no-such-gpu") != std::string::npos);
        CHECK(error.find("llvmpipe") != std::string::npos); // lists what exists
    }
    SECTION("option matching case-insensitively") {
        options.device = "LLVMPIPE";
        std::string error;
        auto runner = VulkanRunner::create(options, &error);
        REQUIRE(runner);
        CHECK_FALSE(runner->device_info().validation_enabled);
    }
    SECTION("environment variable") {
        ScopedEnv env("WATERGEN_VK_DEVICE", "not-a-device");
        std::string error;
        CHECK_FALSE(VulkanRunner::create(options, &error));
        CHECK(error.find("WATERGEN_VK_DEVICE") != std::string::npos);
        CHECK(error.find("not-a-device") != std::string::npos);
        // The option beats the environment.
        options.device = "llvmpipe";
        CHECK(VulkanRunner::create(options, &error));
    }
}

TEST_CASE("no usable Vulkan driver: nullptr and one clear error", "[render][device]") {
    // Point the loader at a driver manifest that does not exist: nothing can load.
    ScopedEnv icd("VK_ICD_FILENAMES", "/nonexistent/watergen_no_icd.json");
    ScopedEnv driver_files("VK_DRIVER_FILES", "/nonexistent/watergen_no_icd.json");
    DeviceOptions options;
    options.validation = false;
    std::string error;
    auto runner = VulkanRunner::create(options, &error);
    INFO(error);
    CHECK_FALSE(runner);
    CHECK(error.find("mesa-vulkan-drivers") != std::string::npos);
}
