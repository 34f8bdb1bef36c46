#include "watergen/toolchain/toolchain.h"

#include "watergen/toolchain/reflection_stage.h"
#include "watergen/toolchain/spirv_cross_stage.h"
#include "watergen/toolchain/spirv_tools_stage.h"

namespace watergen {
namespace {

// Returns true when `from` had errors, so callers can stop the chain.
bool take(Diagnostics& to, Diagnostics from) {
    const bool errors = has_errors(from);
    for (auto& d : from)
        to.push_back(std::move(d));
    return errors;
}

// SPIRV-Cross to GLSL 330, ESSL 300 and MSL from the optimised module, then the round trip of
// the GL texts through glslang.
void cross_compile_and_check(const CompileRequest& request, ToolchainOutputs& out) {
    const std::string& f = request.file_name;
    out.cross_compiled = true;
    // GLSL 330 and ESSL 300 predate compute shaders, so compute only gets MSL; neither has
    // 16-bit arithmetic types (a strict-half module), which MSL has (`half`).
    const bool compute = request.stage == ShaderStage::Compute;
    // Tessellation came to desktop GL in 4.0 and to ES in 3.2 (or GL_EXT_tessellation_shader);
    // SPIRV-Cross writes Metal tessellation only as compute kernels that need the pipeline's
    // other stages and buffers bound in its own way (CompilerMSL::Options::
    // multi_patch_workgroup and friends), which no engine here would load: no MSL either.
    const bool tessellation =
        request.stage == ShaderStage::TessControl || request.stage == ShaderStage::TessEvaluation;
    const bool float16 = declares_capability(out.spirv, kCapabilityFloat16);
    const bool gl_targets = !compute && !tessellation && !float16;
    if (compute)
        out.diagnostics.push_back(
            {Severity::Note, f, 0, 0, "",
             "GLSL 330 and ESSL 300 have no compute shaders; those outputs are skipped"});
    else if (tessellation)
        out.diagnostics.push_back(
            {Severity::Note, f, 0, 0, "",
             "GLSL 330 and ESSL 300 have no tessellation stages (GL 4.0, ES 3.2), and "
             "SPIRV-Cross writes Metal tessellation only as compute kernels with their own "
             "pipeline setup; the GLSL 330, ESSL 300 and MSL outputs are skipped"});
    else if (float16)
        out.diagnostics.push_back(
            {Severity::Note, f, 0, 0, "",
             "GLSL 330 and ESSL 300 have no 16-bit float type; those outputs are skipped"});

    // The back ends are independent: report all of their errors before stopping.
    bool cross_failed = false;
    const struct {
        CrossTarget target;
        std::string* text;
        bool wanted;
    } targets[] = {{CrossTarget::Glsl330, &out.glsl330, gl_targets},
                   {CrossTarget::Essl300, &out.essl300, gl_targets},
                   {CrossTarget::Msl, &out.msl, !tessellation}};
    for (const auto& t : targets) {
        if (!t.wanted) continue;
        CrossResult result = cross_compile(out.spirv_optimized, t.target,
                                           f + cross_target_suffix(t.target), request.msl_bindings);
        cross_failed |= take(out.diagnostics, std::move(result.diagnostics));
        *t.text = std::move(result.source);
    }
    if (cross_failed) return;

    if (!gl_targets) return;
    take(out.diagnostics, check_glsl(out.glsl330, request.stage, GlslProfile::Core330,
                                     f + cross_target_suffix(CrossTarget::Glsl330)));
    take(out.diagnostics, check_glsl(out.essl300, request.stage, GlslProfile::Es300,
                                     f + cross_target_suffix(CrossTarget::Essl300)));
}

} // namespace

ToolchainOutputs run_toolchain(const CompileRequest& request, CrossCompile cross) {
    ToolchainOutputs out;
    const std::string& f = request.file_name;

    SpirvResult compiled = compile_to_spirv(request);
    if (take(out.diagnostics, std::move(compiled.diagnostics)) || compiled.spirv.empty())
        return out;
    if (take(out.diagnostics, validate_spirv(compiled.spirv, f + ".spv"))) return out;
    out.spirv = std::move(compiled.spirv);
    out.instruction_count = count_instructions(out.spirv);

    OptimizeResult optimized = optimize_spirv(out.spirv, f + ".opt.spv");
    if (take(out.diagnostics, std::move(optimized.diagnostics))) return out;
    if (take(out.diagnostics, validate_spirv(optimized.spirv, f + ".opt.spv"))) return out;
    out.spirv_optimized = std::move(optimized.spirv);
    out.instruction_count_optimized = count_instructions(out.spirv_optimized);

    if (cross == CrossCompile::Yes) cross_compile_and_check(request, out);
    if (has_errors(out.diagnostics)) return out;

    ReflectResult reflected = reflect_spirv(out.spirv, request.stage, f + ".spv");
    out.reflection = std::move(reflected.reflection);
    take(out.diagnostics, std::move(reflected.diagnostics));
    return out;
}

} // namespace watergen
