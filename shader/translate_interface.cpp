// Module-scope variables: stage inputs and outputs (user locations and built-ins, copied to and from local memory
// around a run), private variables, push constants and descriptor-backed resources.
#include <algorithm>

#include <spirv/unified1/GLSL.std.450.h>

#include "shader/spirv_names.h"
#include "shader/translator.h"

using SOp = tilevk::shader::Op;

namespace tilevk::shader {

namespace {

uint32_t builtin_bit(spv::BuiltIn b) {
    switch (b) {
        case spv::BuiltIn::Position:
            return bit(BuiltIn::Position);
        case spv::BuiltIn::PointSize:
            return bit(BuiltIn::PointSize);
        case spv::BuiltIn::ClipDistance:
            return bit(BuiltIn::ClipDistance);
        case spv::BuiltIn::CullDistance:
            return bit(BuiltIn::CullDistance);
        case spv::BuiltIn::VertexIndex:
            return bit(BuiltIn::VertexIndex);
        case spv::BuiltIn::InstanceIndex:
            return bit(BuiltIn::InstanceIndex);
        case spv::BuiltIn::BaseVertex:
            return bit(BuiltIn::BaseVertex);
        case spv::BuiltIn::BaseInstance:
            return bit(BuiltIn::BaseInstance);
        case spv::BuiltIn::DrawIndex:
            return bit(BuiltIn::DrawIndex);
        case spv::BuiltIn::ViewIndex:
            return bit(BuiltIn::ViewIndex);
        case spv::BuiltIn::FragCoord:
            return bit(BuiltIn::FragCoord);
        case spv::BuiltIn::FrontFacing:
            return bit(BuiltIn::FrontFacing);
        case spv::BuiltIn::PointCoord:
            return bit(BuiltIn::PointCoord);
        case spv::BuiltIn::FragDepth:
            return bit(BuiltIn::FragDepth);
        case spv::BuiltIn::SampleMask:
            return bit(BuiltIn::SampleMask);
        case spv::BuiltIn::SampleId:
            return bit(BuiltIn::SampleId);
        case spv::BuiltIn::SamplePosition:
            return bit(BuiltIn::SamplePosition);
        case spv::BuiltIn::HelperInvocation:
            return bit(BuiltIn::HelperInvocation);
        case spv::BuiltIn::LocalInvocationId:
            return bit(BuiltIn::LocalInvocationId);
        case spv::BuiltIn::LocalInvocationIndex:
            return bit(BuiltIn::LocalInvocationIndex);
        case spv::BuiltIn::GlobalInvocationId:
            return bit(BuiltIn::GlobalInvocationId);
        case spv::BuiltIn::WorkgroupId:
            return bit(BuiltIn::WorkgroupId);
        case spv::BuiltIn::NumWorkgroups:
            return bit(BuiltIn::NumWorkgroups);
        default:
            return 0;
    }
}

// Which IoSlot a builtin maps to, given the stage and direction; fails for anything unsupported.
IoSlot builtin_slot(spv::BuiltIn b, Stage stage, bool output) {
    std::string where = std::string(stage_name(stage)) + (output ? " output" : " input");
    if (stage == Stage::Compute) {
        if (!output && b == spv::BuiltIn::LocalInvocationId) return IoSlot::LocalInvocationId;
        if (!output && b == spv::BuiltIn::LocalInvocationIndex) return IoSlot::LocalInvocationIndex;
        if (!output && b == spv::BuiltIn::GlobalInvocationId) return IoSlot::GlobalInvocationId;
        if (!output && b == spv::BuiltIn::WorkgroupId) return IoSlot::WorkgroupId;
        if (!output && b == spv::BuiltIn::NumWorkgroups) return IoSlot::NumWorkgroups;
        if (!output) {
            switch (b) {
                case spv::BuiltIn::SubgroupSize:
                    return IoSlot::SubgroupSize;
                case spv::BuiltIn::SubgroupLocalInvocationId:
                    return IoSlot::SubgroupLocalInvocationId;
                case spv::BuiltIn::SubgroupId:
                    return IoSlot::SubgroupId;
                case spv::BuiltIn::NumSubgroups:
                    return IoSlot::NumSubgroups;
                case spv::BuiltIn::SubgroupEqMask:
                    return IoSlot::SubgroupEqMask;
                case spv::BuiltIn::SubgroupGeMask:
                    return IoSlot::SubgroupGeMask;
                case spv::BuiltIn::SubgroupGtMask:
                    return IoSlot::SubgroupGtMask;
                case spv::BuiltIn::SubgroupLeMask:
                    return IoSlot::SubgroupLeMask;
                case spv::BuiltIn::SubgroupLtMask:
                    return IoSlot::SubgroupLtMask;
                default:
                    break;
            }
        }
    } else if (stage == Stage::Vertex && !output) {
        if (b == spv::BuiltIn::VertexIndex) return IoSlot::VertexIndex;
        if (b == spv::BuiltIn::InstanceIndex) return IoSlot::InstanceIndex;
        if (b == spv::BuiltIn::BaseVertex) return IoSlot::BaseVertex;
        if (b == spv::BuiltIn::BaseInstance) return IoSlot::BaseInstance;
        if (b == spv::BuiltIn::DrawIndex) return IoSlot::DrawIndex;
        if (b == spv::BuiltIn::ViewIndex) return IoSlot::ViewIndex;
    } else if (stage == Stage::Vertex && output) {
        if (b == spv::BuiltIn::Position) return IoSlot::Position;
        if (b == spv::BuiltIn::PointSize) return IoSlot::PointSize;
        if (b == spv::BuiltIn::ClipDistance) return IoSlot::ClipDistance;
        if (b == spv::BuiltIn::CullDistance) return IoSlot::CullDistance;
    } else if (!output) {
        if (b == spv::BuiltIn::FragCoord) return IoSlot::FragCoord;
        if (b == spv::BuiltIn::FrontFacing) return IoSlot::FrontFacing;
        if (b == spv::BuiltIn::PointCoord) return IoSlot::PointCoord;
        if (b == spv::BuiltIn::SampleMask) return IoSlot::SampleMaskIn;
        if (b == spv::BuiltIn::SampleId) return IoSlot::SampleId;
        if (b == spv::BuiltIn::SamplePosition) return IoSlot::SamplePosition;
        if (b == spv::BuiltIn::HelperInvocation) return IoSlot::HelperInvocation;
        if (b == spv::BuiltIn::ViewIndex) return IoSlot::ViewIndex;
    } else {
        if (b == spv::BuiltIn::FragDepth) return IoSlot::FragDepth;
        if (b == spv::BuiltIn::SampleMask) return IoSlot::SampleMask;
    }
    Translator::fail(std::string("unsupported builtin ") + names::builtin(uint32_t(b)) + " as " + where);
}

// Locations a member or array element of type `t` occupies.
uint32_t locations_of(const Translator& tr, uint32_t t) {
    const Type& ty = tr.type(t);
    if (ty.kind == Type::Array) return ty.count * (tr.type(ty.elem).kind == Type::Matrix ? tr.type(ty.elem).count : 1);
    return ty.kind == Type::Matrix ? ty.count : 1;
}

}  // namespace

void Translator::declare_variable(const Instr& in) {
    const Type& pt = type(in[1]);
    spv::StorageClass sc = spv::StorageClass(in[3]);
    uint32_t id = in[2];
    const Type& t = type(pt.elem);
    Pointer p;
    p.type = pt.elem;
    switch (sc) {
        case spv::StorageClass::Private:
        case spv::StorageClass::Input:
        case spv::StorageClass::Output: {
            p.space = Space::Local;
            p.base = local_words_;
            p.limit = local_words_ + t.flat;
            local_words_ += t.flat;
            if (in.n > 4) private_inits_.push_back({uint32_t(pointers_.size()), in[4]});
            if (sc != spv::StorageClass::Private &&
                std::find(entry_iface_.begin(), entry_iface_.end(), id) != entry_iface_.end()) {
                const Decorations& d = deco_[id];
                walk_interface(sc == spv::StorageClass::Output, pt.elem, p.base, d.location, d.component, d, d.builtin);
            }
            break;
        }
        case spv::StorageClass::PushConstant:
            p.space = Space::Buffer;
            p.base = 0;
            p.limit = 1;
            break;
        case spv::StorageClass::Uniform:
        case spv::StorageClass::StorageBuffer:
        case spv::StorageClass::UniformConstant:
            declare_resource(sc, deco_[id], p);
            break;
        case spv::StorageClass::Workgroup:
            if (stage_ != Stage::Compute) fail("Workgroup storage outside a compute shader");
            // shaderZeroInitializeWorkgroupMemory: run_workgroup zeroes the block before every workgroup, so a zero
            // initializer (OpConstantNull, the only one SPIR-V allows here) holds without running anything.
            if (in.n > 4 && !is_zero_constant(in[4], t.flat))
                fail("Workgroup variable initializer other than zero (shaderZeroInitializeWorkgroupMemory)");
            p.space = Space::Shared;
            p.base = shared_words_;
            p.limit = shared_words_ + t.flat;
            shared_words_ += t.flat;
            // far past any device's maxComputeSharedMemorySize; keeps the byte count in 32 bits
            if (shared_words_ > (1u << 24)) fail("Workgroup variables of more than 64 MiB");
            break;
        case spv::StorageClass::Function:
            fail("function variable at module scope");
        default:
            fail(std::string("unsupported storage class ") + names::storage_class(in[3]));
    }
    pointers_.push_back(p);
    vals_[id] = Value{kNoReg, in[1], int(pointers_.size() - 1)};
}

// An interface variable (or a member / element of one) at local word `word`: records the copies in or out of the
// run and the reflection entry.
void Translator::walk_interface(bool out, uint32_t ty, uint32_t word, int loc, int comp, const Decorations& dd,
                                int builtin) {
    const Type& tt = type(ty);
    if (builtin >= 0) {
        IoSlot s = builtin_slot(spv::BuiltIn(builtin), stage_, out);
        uint32_t b = builtin_bit(spv::BuiltIn(builtin));
        (out ? iface_.builtins_written : iface_.builtins_read) |= b;
        if (s == IoSlot::FragDepth) iface_.writes_frag_depth = true;
        uint32_t n = tt.flat;
        if (s == IoSlot::ClipDistance) iface_.clip_distances = n;
        if (s == IoSlot::CullDistance) iface_.cull_distances = n;
        if (out && (s == IoSlot::ClipDistance || s == IoSlot::CullDistance)) {
            uint32_t* range = distance_words_[s == IoSlot::ClipDistance ? 0 : 1];
            range[0] = word;
            range[1] = word + n;
        }
        if ((s == IoSlot::ClipDistance || s == IoSlot::CullDistance) && n > kMaxClipDistances)
            fail("too many clip/cull distances");
        for (uint32_t j = 0; j < n; ++j) (out ? p_.io_out : p_.io_in).push_back(IoCopy{s, j, word + j});
        return;
    }
    if (tt.kind == Type::Struct) {
        int l = loc;
        uint32_t w = word;
        for (uint32_t m = 0; m < tt.members.size(); ++m) {
            auto it = member_deco_.find({ty, m});
            Decorations md = it != member_deco_.end() ? it->second : Decorations{};
            if (md.location >= 0) l = md.location;
            md.flat |= dd.flat;
            md.noperspective |= dd.noperspective;
            md.centroid |= dd.centroid;
            md.sample |= dd.sample;
            if (md.builtin < 0 && l < 0) fail("interface block member without a location");
            walk_interface(out, tt.members[m], w, l, md.component, md, md.builtin);
            if (md.builtin < 0) l += int(locations_of(*this, tt.members[m]));
            w += type(tt.members[m]).flat;
        }
        return;
    }
    if (tt.kind == Type::Array || tt.kind == Type::Matrix) {
        uint32_t ef = type(tt.elem).flat;
        uint32_t el = type(tt.elem).kind == Type::Matrix ? type(tt.elem).count : 1;
        for (uint32_t i = 0; i < tt.count; ++i)
            walk_interface(out, tt.elem, word + i * ef, loc + int(i * el), comp, dd, -1);
        return;
    }
    if (loc < 0) fail("interface variable without a location");
    uint32_t n = tt.flat;
    if (n > 4 || comp + n > 4) fail("interface variable wider than 4 components");
    int maxloc = out && stage_ == Stage::Fragment ? kMaxColorOutputs : kMaxLocations;
    if (loc >= maxloc) fail("location " + std::to_string(loc) + " out of range");
    if (out && stage_ == Stage::Fragment && dd.index == 1) {
        // The second source of dual-source blending (maxFragmentDualSrcAttachments 1).
        if (loc != 0)
            fail("fragment output Location " + std::to_string(loc) + " with Index 1: only Location 0 has one");
        loc = kSecondColorOutput;
    }
    for (uint32_t j = 0; j < n; ++j)
        (out ? p_.io_out : p_.io_in)
            .push_back(IoCopy{out ? IoSlot::Output : IoSlot::Input, uint32_t(loc * 4 + comp + int(j)), word + j});
    IoVariable v;
    v.location = uint32_t(loc);
    v.component = uint32_t(comp);
    v.components = n;
    uint32_t st = component_type(ty);
    v.type = types_[st].kind == Type::Float ? ScalarType::Float
             : types_[st].is_signed         ? ScalarType::Int
                                            : ScalarType::Uint;
    v.interpolation = dd.flat            ? Interpolation::Flat
                      : dd.noperspective ? Interpolation::NoPerspective
                                         : Interpolation::Smooth;
    v.centroid = dd.centroid;
    v.sample = dd.sample;
    (out ? iface_.outputs : iface_.inputs).push_back(v);
}

// A descriptor-backed variable (buffer block, image, sampler, or an array of them): takes consecutive slots.
void Translator::declare_resource(spv::StorageClass sc, const Decorations& d, Pointer& p) {
    if (d.set < 0 || d.binding < 0) fail("resource variable without DescriptorSet/Binding");
    const Type& t = type(p.type);
    uint32_t count = 1;
    uint32_t inner = p.type;
    if (t.kind == Type::Array) {
        count = t.count;
        inner = t.elem;
        p.in_array = true;
    } else if (t.kind == Type::RuntimeArray) {
        fail("unsupported runtime-sized descriptor array");
    }
    const Type& it = type(inner);
    DescriptorUse use;
    use.set = uint32_t(d.set);
    use.binding = uint32_t(d.binding);
    use.array_size = count;
    if (sc == spv::StorageClass::UniformConstant) {
        p.space = Space::Handle;
        if (it.kind == Type::SampledImage)
            use.kind = DescriptorKind::CombinedImageSampler;
        else if (it.kind == Type::Image)
            use.kind = it.sampled == 2 ? DescriptorKind::StorageImage : DescriptorKind::SampledImage;
        else if (it.kind == Type::Sampler)
            use.kind = DescriptorKind::Sampler;
        else
            fail("unsupported UniformConstant variable type");
    } else {
        p.space = Space::Buffer;
        bool ssbo = sc == spv::StorageClass::StorageBuffer || deco_[inner].buffer_block;
        use.kind = ssbo ? DescriptorKind::StorageBuffer : DescriptorKind::UniformBuffer;
        p.writable = ssbo;
    }
    p.base = next_slot_;
    p.limit = count;
    p_.slots.push_back(SlotBinding{use.set, use.binding, count});
    next_slot_ += count;
    if (next_slot_ > (1u << 15)) fail("too many descriptors");
    iface_.descriptors.push_back(use);
}

// GLSL.std.450 InterpolateAtCentroid / AtSample / AtOffset (in[5] the interpolant, in[6] the sample or offset): one
// Op::InterpolateAt per component of the input the pointer names, re-evaluated from the block's attribute planes
// (shader/interpolate.cpp). The pointer must name whole components of Input locations at constant words.
void Translator::interpolate_at(const Instr& in, uint32_t e) {
    const std::string what = std::string("GLSL.std.450 ") + glsl_std450_name(e);
    if (stage_ != Stage::Fragment) fail(what + " outside a fragment shader");
    const Value& pv = val(in[5]);
    if (pv.ptr < 0) fail(what + ": the interpolant is not a pointer");
    const Pointer& p = pointers_[size_t(pv.ptr)];
    if (p.space != Space::Local) fail(what + ": the interpolant is not an Input variable");
    if (p.dyn != kNoReg) fail(what + " on a dynamically indexed input (not implemented)");
    const uint32_t n = std::max(1u, type(in[1]).flat);
    uint32_t x = kNoReg, y = kNoReg;
    auto mode = InterpAt::Centroid;
    if (e == GLSLstd450InterpolateAtSample) {
        mode = InterpAt::Sample;
        x = reg(in[6]);
    } else if (e == GLSLstd450InterpolateAtOffset) {
        mode = InterpAt::Offset;
        x = reg(in[6]);
        y = x + 1;
    }
    const uint32_t d = alloc(n);
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t word = p.base + p.offset + i;
        const auto it = std::find_if(p_.io_in.begin(), p_.io_in.end(),
                                     [&](const IoCopy& c) { return c.slot == IoSlot::Input && c.word == word; });
        if (it == p_.io_in.end()) fail(what + ": the interpolant is not a user Input variable");
        emit(SOp::InterpolateAt, d + i, x, y, kNoReg, it->index).pad = uint16_t(mode);
    }
    vals_[in[2]] = Value{d, in[1]};
    iface_.interpolates_at = true;
}

}  // namespace tilevk::shader
