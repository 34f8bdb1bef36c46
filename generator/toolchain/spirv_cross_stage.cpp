#include "watergen/toolchain/spirv_cross_stage.h"

#include <exception>
#include <map>
#include <memory>

#include <spirv_cross/spirv_glsl.hpp>
#include <spirv_cross/spirv_msl.hpp>

namespace watergen {
namespace {

// SPIRV-Cross would otherwise call combined samplers "SPIRV_Cross_Combined<image><sampler>",
// which engines would have to hard-code when binding textures by name.
void name_combined_samplers(spirv_cross::CompilerGLSL& compiler) {
    std::map<uint32_t, int> uses_per_image;
    for (const auto& c : compiler.get_combined_image_samplers())
        ++uses_per_image[uint32_t(c.image_id)];
    for (const auto& c : compiler.get_combined_image_samplers()) {
        std::string image = compiler.get_name(c.image_id);
        if (image.empty()) image = "texture" + std::to_string(uint32_t(c.image_id));
        std::string name = image;
        if (uses_per_image[uint32_t(c.image_id)] > 1) {
            std::string sampler = compiler.get_name(c.sampler_id);
            if (sampler.empty()) sampler = "sampler" + std::to_string(uint32_t(c.sampler_id));
            name += "_" + sampler;
        }
        compiler.set_name(c.combined_id, name);
    }
}

std::string compile_gl(const std::vector<uint32_t>& spirv, bool es) {
    spirv_cross::CompilerGLSL compiler(spirv);
    spirv_cross::CompilerGLSL::Options options;
    options.version = es ? 300 : 330;
    options.es = es;
    options.vulkan_semantics = false;
    // Without this SPIRV-Cross emits layout(binding) via GL_ARB_shading_language_420pack,
    // which plain 330 core drivers (and glslang in 330 mode) reject.
    options.enable_420pack_extension = false;
    // A push-constant block becomes a uniform block an engine binds like the Vulkan path's
    // (glUniformBlockBinding at the map's GL binding), not a struct of loose uniforms.
    options.emit_push_constant_as_uniform_buffer = true;
    // Water needs world-space precision in the fragment stage; ES 3.0 guarantees highp there.
    options.fragment.default_float_precision = spirv_cross::CompilerGLSL::Options::Highp;
    options.fragment.default_int_precision = spirv_cross::CompilerGLSL::Options::Highp;
    compiler.set_common_options(options);
    compiler.build_combined_image_samplers();
    name_combined_samplers(compiler);
    return compiler.compile();
}

std::string compile_msl(const std::vector<uint32_t>& spirv, const std::vector<MslSlot>& slots) {
    spirv_cross::CompilerMSL compiler(spirv);
    for (const MslSlot& s : slots) {
        spirv_cross::MSLResourceBinding b;
        b.stage = compiler.get_execution_model();
        b.desc_set = s.push_constant ? spirv_cross::kPushConstDescSet : s.set;
        b.binding = s.push_constant ? spirv_cross::kPushConstBinding : s.binding;
        b.count = 1;
        // Only the field of the resource's kind is read.
        b.msl_buffer = b.msl_texture = b.msl_sampler = s.index;
        compiler.add_msl_resource_binding(b);
    }
    return compiler.compile();
}

} // namespace

const char* cross_target_suffix(CrossTarget target) {
    switch (target) {
    case CrossTarget::Glsl330:
        return ".330.glsl";
    case CrossTarget::Essl300:
        return ".300es.glsl";
    case CrossTarget::Msl:
        return ".metal";
    }
    return "";
}

CrossResult cross_compile(const std::vector<uint32_t>& spirv, CrossTarget target,
                          const std::string& file_name, const std::vector<MslSlot>& msl) {
    CrossResult result;
    // SPIRV-Cross reports every problem by throwing; stages must return errors as data.
    try {
        switch (target) {
        case CrossTarget::Glsl330:
            result.source = compile_gl(spirv, false);
            break;
        case CrossTarget::Essl300:
            result.source = compile_gl(spirv, true);
            break;
        case CrossTarget::Msl:
            result.source = compile_msl(spirv, msl);
            break;
        }
    } catch (const spirv_cross::CompilerError& e) {
        result.source.clear();
        result.diagnostics.push_back(
            {Severity::Error, file_name, 0, 0, "", std::string("spirv-cross: ") + e.what()});
    } catch (const std::exception& e) {
        result.source.clear();
        result.diagnostics.push_back({Severity::Error, file_name, 0, 0, "",
                                      std::string("spirv-cross: internal error: ") + e.what()});
    }
    return result;
}

} // namespace watergen
