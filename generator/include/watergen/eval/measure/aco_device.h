// AMD's shader compiler without an AMD GPU: Mesa's RADV driver opens a "null hardware" device
// for the family named in RADV_FORCE_FAMILY, whose pipelines compile through ACO (the compiler
// AMD GPUs run on Linux and the Steam Deck) and report its statistics through
// VK_KHR_pipeline_executable_properties. The device has no memory heaps: it creates render
// passes and pipelines and nothing it would draw with.
//
// This is the worker's side (aco_worker.h runs it in a child process with the environment set:
// radv aborts the process on a family it does not know, and a compiler crash takes the process
// with it).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "watergen/eval/measure/aco_loops.h"
#include "watergen/runtime/reflection.h"
#include "watergen/runtime/variant_pipeline.h"

namespace watergen {

// One pipeline to compile: the stages as a build writes them, the specialization constants by
// id (a specialized build's selector values); the water pass's fullscreen triangle into an
// RGBA16F target, a mesh variant's grid (geometry: its vertex input, patches for the
// tessellation stages), or a companion pass's grid into its own float target.
struct AcoPipelineSource {
    std::string name;
    std::vector<uint32_t> vertex, fragment;
    Reflection vertex_reflection, fragment_reflection;
    // A tessellated mesh's patch stages (both or neither; empty: none).
    std::vector<uint32_t> tess_control, tess_evaluation;
    Reflection tess_control_reflection, tess_evaluation_reflection;
    std::map<uint32_t, float> specialization;
    std::optional<PipelineGeometry> geometry; // a companion pass (pass_geometry())
    VkFormat format = VK_FORMAT_R16G16B16A16_SFLOAT;
};

// What the driver reports for one executable of a pipeline (a stage, or stages merged: RADV
// names them "Vertex Shader", "Fragment Shader", ...).
struct AcoStageStatistics {
    // "vertex", "tess_control", "tess_evaluation" or "fragment": the lowest stage the
    // executable holds (RADV merges the vertex and tessellation control stages from gfx9 on).
    std::string stage;
    std::string executable; // the driver's name for it
    uint32_t subgroup_size = 0;
    // Every statistic the driver reports, by its name ("Instructions", "VGPRs", ...).
    std::map<std::string, double> values;
    // The loops of its disassembly (empty when the driver gave none).
    std::vector<AsmLoop> loops;
    bool has_disassembly = false;
    double value(const std::string& name) const; // -1 when not reported
};

struct AcoPipelineStatistics {
    std::string name;
    std::vector<AcoStageStatistics> stages;
    std::string error; // the driver refused it: the Vulkan call and its result
    // Not compiled: the shader needs a feature the family lacks (16-bit arithmetic on gcn1);
    // `error` says which. Not a driver fault: the shader cannot run on that GPU.
    bool unsupported = false;
    bool ok() const { return error.empty(); }
};

class AcoDevice {
  public:
    // The null device of the family RADV_FORCE_FAMILY names, with the pipeline executable
    // feature and the 16-bit shader features it has; nullptr and *error when the loader finds
    // no RADV device or it lacks VK_KHR_pipeline_executable_properties.
    // `disassembly`: capture ACO's disassembly (for the loops); Mesa disassembles gfx6 through
    // CLRX, which Debian does not package, so gcn1 goes without.
    static std::unique_ptr<AcoDevice> open(std::string* error, bool disassembly = true);
    ~AcoDevice();
    AcoDevice(const AcoDevice&) = delete;
    AcoDevice& operator=(const AcoDevice&) = delete;

    const std::string& name() const { return name_; }        // "AMD RADV NAVI21"
    const std::string& driver_info() const { return info_; } // "Mesa 22.3.6 (LLVM 15.0.6)"

    // Compiles the pipeline with statistics and internal representations captured.
    // Cost: 2-20 ms.
    AcoPipelineStatistics compile(const AcoPipelineSource& source);

    struct Handles; // the Vulkan objects (aco_device.cpp)

  private:
    AcoDevice() = default;
    std::unique_ptr<Handles> h_;
    std::string name_, info_;
    bool float16_ = false, disassembly_ = true;
};

} // namespace watergen
