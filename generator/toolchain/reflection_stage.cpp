#include "watergen/toolchain/reflection_stage.h"

#include <algorithm>
#include <exception>

#include <spirv_cross/spirv_cross.hpp>

namespace watergen {
namespace {

spv::ExecutionModel to_model(ShaderStage stage) {
    switch (stage) {
    case ShaderStage::Vertex:
        return spv::ExecutionModelVertex;
    case ShaderStage::Fragment:
        return spv::ExecutionModelFragment;
    case ShaderStage::Compute:
        return spv::ExecutionModelGLCompute;
    case ShaderStage::TessControl:
        return spv::ExecutionModelTessellationControl;
    case ShaderStage::TessEvaluation:
        return spv::ExecutionModelTessellationEvaluation;
    }
    return spv::ExecutionModelFragment;
}

std::string glsl_type(const spirv_cross::Compiler& compiler, const spirv_cross::SPIRType& t) {
    using BT = spirv_cross::SPIRType::BaseType;
    std::string name;
    if (t.basetype == BT::Struct) {
        name = compiler.get_name(t.self);
    } else {
        std::string scalar, prefix;
        switch (t.basetype) {
        case BT::Float:
            scalar = "float";
            break;
        case BT::Double:
            scalar = "double";
            prefix = "d";
            break;
        case BT::Int:
            scalar = "int";
            prefix = "i";
            break;
        case BT::UInt:
            scalar = "uint";
            prefix = "u";
            break;
        case BT::Boolean:
            scalar = "bool";
            prefix = "b";
            break;
        default:
            scalar = "unknown";
            break;
        }
        if (t.columns > 1) {
            name = prefix + "mat" + std::to_string(t.columns);
            if (t.columns != t.vecsize) name += "x" + std::to_string(t.vecsize);
        } else if (t.vecsize > 1) {
            name = prefix + "vec" + std::to_string(t.vecsize);
        } else {
            name = scalar;
        }
    }
    // SPIR-V lists array dimensions innermost first; GLSL writes the outermost first.
    for (size_t i = t.array.size(); i-- > 0;) {
        const bool literal = i < t.array_size_literal.size() && t.array_size_literal[i];
        name += (literal && t.array[i] != 0) ? "[" + std::to_string(t.array[i]) + "]" : "[]";
    }
    return name;
}

std::string image_dim(const spirv_cross::SPIRType& t) {
    switch (t.image.dim) {
    case spv::Dim1D:
        return "1D";
    case spv::Dim2D:
        return "2D";
    case spv::Dim3D:
        return "3D";
    case spv::DimCube:
        return "Cube";
    default:
        return "other";
    }
}

DescriptorBinding base_binding(const spirv_cross::Compiler& compiler,
                               const spirv_cross::Resource& r, DescriptorKind kind) {
    DescriptorBinding b;
    b.name = r.name.empty() ? compiler.get_fallback_name(r.id) : r.name;
    b.set = compiler.get_decoration(r.id, spv::DecorationDescriptorSet);
    b.binding = compiler.get_decoration(r.id, spv::DecorationBinding);
    b.kind = kind;
    return b;
}

DescriptorBinding block_binding(const spirv_cross::Compiler& compiler,
                                const spirv_cross::Resource& r, DescriptorKind kind) {
    DescriptorBinding b = base_binding(compiler, r, kind);
    // The block type name is what both front ends agree on: GLSL's instance name
    // ("params") has no HLSL counterpart, a cbuffer's variable is anonymous.
    const std::string& type_name = compiler.get_name(r.base_type_id);
    if (!type_name.empty()) b.name = type_name;
    const auto& type = compiler.get_type(r.base_type_id);
    b.block_size = uint32_t(compiler.get_declared_struct_size(type));
    for (uint32_t i = 0; i < uint32_t(type.member_types.size()); ++i) {
        UniformMember m;
        m.name = compiler.get_member_name(r.base_type_id, i);
        m.type = glsl_type(compiler, compiler.get_type(type.member_types[i]));
        m.offset = compiler.type_struct_member_offset(type, i);
        m.size = uint32_t(compiler.get_declared_struct_member_size(type, i));
        const auto& member_type = compiler.get_type(type.member_types[i]);
        if (!member_type.array.empty()) {
            m.array_size = member_type.array.back(); // outermost dimension
            m.array_stride = compiler.type_struct_member_array_stride(type, i);
        }
        b.members.push_back(std::move(m));
    }
    return b;
}

std::vector<StageVariable>
stage_variables(const spirv_cross::Compiler& compiler,
                const spirv_cross::SmallVector<spirv_cross::Resource>& resources) {
    std::vector<StageVariable> vars;
    for (const auto& r : resources) {
        if (compiler.has_decoration(r.id, spv::DecorationBuiltIn)) continue;
        StageVariable v;
        v.name = r.name.empty() ? compiler.get_fallback_name(r.id) : r.name;
        v.location = compiler.get_decoration(r.id, spv::DecorationLocation);
        v.type = glsl_type(compiler, compiler.get_type(r.type_id));
        vars.push_back(std::move(v));
    }
    std::stable_sort(vars.begin(), vars.end(), [](const StageVariable& a, const StageVariable& b) {
        return a.location < b.location;
    });
    return vars;
}

// Scalar specialization constants (a composite of them has no SpecId of its own); the range is
// not in the module, so it stays 0 for the caller to fill.
std::vector<SpecializationConstant>
specialization_constants(const spirv_cross::Compiler& compiler) {
    using BT = spirv_cross::SPIRType::BaseType;
    std::vector<SpecializationConstant> out;
    for (const auto& sc : compiler.get_specialization_constants()) {
        const spirv_cross::SPIRConstant& value = compiler.get_constant(sc.id);
        const spirv_cross::SPIRType& type = compiler.get_type(value.constant_type);
        SpecializationConstant c;
        c.id = sc.constant_id;
        c.name = compiler.get_name(sc.id);
        if (c.name.empty()) c.name = compiler.get_fallback_name(sc.id);
        c.type = glsl_type(compiler, type);
        switch (type.basetype) {
        case BT::Float:
            c.default_value = value.scalar_f32();
            break;
        case BT::Int:
            c.default_value = value.scalar_i32();
            break;
        case BT::UInt:
        case BT::Boolean:
            c.default_value = value.scalar();
            break;
        default:
            break;
        }
        out.push_back(std::move(c));
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const auto& a, const auto& b) { return a.id < b.id; });
    return out;
}

void warn_unsupported(const spirv_cross::Compiler& compiler,
                      const spirv_cross::SmallVector<spirv_cross::Resource>& resources,
                      const char* kind, const std::string& file, Diagnostics& ds) {
    for (const auto& r : resources) {
        const std::string name = r.name.empty() ? compiler.get_fallback_name(r.id) : r.name;
        ds.push_back(
            {Severity::Warning, file, 0, 0, "",
             "reflect: " + std::string(kind) + " '" + name + "' is not described by Reflection"});
    }
}

void reflect_into(spirv_cross::Compiler& compiler, ShaderStage stage, const std::string& file,
                  ReflectResult& out) {
    Reflection& refl = out.reflection;
    refl.stage = stage;
    const spv::ExecutionModel model = to_model(stage);
    bool found = false;
    for (const auto& ep : compiler.get_entry_points_and_stages()) {
        if (ep.execution_model == model) {
            refl.entry_point = ep.name;
            found = true;
            break;
        }
    }
    if (!found) {
        out.diagnostics.push_back(
            {Severity::Error, file, 0, 0, "",
             std::string("reflect: module has no ") + to_string(stage) + " entry point"});
        return;
    }
    compiler.set_entry_point(refl.entry_point, model);

    // Only what the entry point statically uses: the HLSL path (front end + legalisation)
    // drops unreferenced globals and inputs while the GLSL path keeps them, so "everything
    // declared" would make the two paths disagree about a shader with an unused texture.
    const spirv_cross::ShaderResources res =
        compiler.get_shader_resources(compiler.get_active_interface_variables());
    for (const auto& r : res.uniform_buffers)
        refl.bindings.push_back(block_binding(compiler, r, DescriptorKind::UniformBuffer));
    for (const auto& r : res.storage_buffers)
        refl.bindings.push_back(block_binding(compiler, r, DescriptorKind::StorageBuffer));
    for (const auto& r : res.separate_images) {
        DescriptorBinding b = base_binding(compiler, r, DescriptorKind::SampledImage);
        b.image_dim = image_dim(compiler.get_type(r.base_type_id));
        refl.bindings.push_back(std::move(b));
    }
    for (const auto& r : res.separate_samplers)
        refl.bindings.push_back(base_binding(compiler, r, DescriptorKind::Sampler));
    for (const auto& r : res.sampled_images) {
        DescriptorBinding b = base_binding(compiler, r, DescriptorKind::CombinedImageSampler);
        b.image_dim = image_dim(compiler.get_type(r.base_type_id));
        refl.bindings.push_back(std::move(b));
    }
    std::stable_sort(refl.bindings.begin(), refl.bindings.end(), [](const auto& a, const auto& b) {
        return a.set != b.set ? a.set < b.set : a.binding < b.binding;
    });

    warn_unsupported(compiler, res.storage_images, "storage image", file, out.diagnostics);
    // One push-constant block (the parameter block, when the binding map makes it one); a
    // module holds at most one per entry point.
    for (const auto& r : res.push_constant_buffers) {
        refl.push_constant = block_binding(compiler, r, DescriptorKind::PushConstant);
        refl.push_constant->set = refl.push_constant->binding = 0;
    }
    warn_unsupported(compiler, res.subpass_inputs, "subpass input", file, out.diagnostics);
    warn_unsupported(compiler, res.atomic_counters, "atomic counter", file, out.diagnostics);
    warn_unsupported(compiler, res.acceleration_structures, "acceleration structure", file,
                     out.diagnostics);

    // Same reason for stage I/O: HLSL legalisation removes an input nobody reads.
    refl.inputs = stage_variables(compiler, res.stage_inputs);
    refl.outputs = stage_variables(compiler, res.stage_outputs);
    refl.specialization_constants = specialization_constants(compiler);
}

} // namespace

ReflectResult reflect_spirv(const std::vector<uint32_t>& spirv, ShaderStage stage,
                            const std::string& file_name) {
    ReflectResult out;
    out.reflection.stage = stage;
    // SPIRV-Cross throws on malformed modules; stages return errors as data.
    try {
        spirv_cross::Compiler compiler(spirv);
        reflect_into(compiler, stage, file_name, out);
    } catch (const std::exception& e) {
        out.diagnostics.push_back(
            {Severity::Error, file_name, 0, 0, "", std::string("reflect: ") + e.what()});
    }
    return out;
}

} // namespace watergen
