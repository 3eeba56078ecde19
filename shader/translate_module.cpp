// Module-level declarations: capabilities, extensions, execution modes, decorations, types and constants
// (variables are declared in translate_interface.cpp).
#include <algorithm>
#include <cstring>

#include "shader/spirv_names.h"
#include "shader/translator.h"

namespace tilevk::shader {

std::string literal_string(const Instr& in, size_t at) {
    if (at >= in.n) return {};
    return std::string(reinterpret_cast<const char*>(in.w + at),
                       strnlen(reinterpret_cast<const char*>(in.w + at), (in.n - at) * 4));
}

namespace {

bool capability_supported(spv::Capability c) {
    switch (c) {
        case spv::Capability::Shader:
        case spv::Capability::Matrix:
        case spv::Capability::ClipDistance:
        case spv::Capability::CullDistance:
        case spv::Capability::DerivativeControl:
        case spv::Capability::DrawParameters:
        case spv::Capability::GroupNonUniform:  // compute only (translate_subgroup.cpp): other stages fail by op
        case spv::Capability::GroupNonUniformVote:
        case spv::Capability::GroupNonUniformBallot:
        case spv::Capability::MultiView:  // ViewIndex: the view the renderer runs (icd/execute.cpp)
        case spv::Capability::ImageQuery:
        case spv::Capability::SampleRateShading:
        case spv::Capability::DemoteToHelperInvocation:
        // Integer dot products on 32-bit vectors and packed 4x8-bit scalars (translate_dot.cpp); not
        // DotProductInput4x8Bit, whose 8-bit vectors need Int8.
        // The Vulkan memory model (translate_memory.cpp, translate_atomic.cpp): its operands order nothing more
        // than tilevk already does (README "Compute").
        case spv::Capability::VulkanMemoryModel:
        case spv::Capability::VulkanMemoryModelDeviceScope:
        case spv::Capability::DotProduct:
        case spv::Capability::DotProductInputAll:
        case spv::Capability::DotProductInput4x8BitPacked:
        case spv::Capability::Sampled1D:
        case spv::Capability::SampledCubeArray:  // samplerCubeArray (shader/texture_cube.cpp)
        case spv::Capability::InputAttachment:  // subpassLoad: a texel fetch at the fragment's pixel
        case spv::Capability::SampledBuffer:    // uniform texel buffers: texelFetch / textureSize only
        case spv::Capability::ImageBuffer:      // storage texel buffers: imageLoad / imageStore / atomics / imageSize
        case spv::Capability::StorageImageExtendedFormats:
        // Stores to a storage image or texel buffer declared without a format (Unknown): the view's format decides
        // the conversion anyway (the image type's format is not read), as in llvmpipe, whose only formatted-access
        // cap is PIPE_CAP_IMAGE_STORE_FORMATTED; reads without a format stay refused as there.
        case spv::Capability::StorageImageWriteWithoutFormat:
        case spv::Capability::InterpolationFunction:  // InterpolateAt*: translate_interface.cpp interpolate_at
        case spv::Capability::ShaderNonUniform:
        case spv::Capability::SampledImageArrayDynamicIndexing:
        case spv::Capability::UniformBufferArrayDynamicIndexing:
        case spv::Capability::StorageBufferArrayDynamicIndexing:
        // Buffer device addresses (translate_pointer.cpp).
        case spv::Capability::PhysicalStorageBufferAddresses:
        // 64-bit integers and doubles: two registers per scalar, translate_wide.cpp (shaderInt64, shaderFloat64)
        case spv::Capability::Int64:
        case spv::Capability::Float64:
        // 8- and 16-bit integers, and 8- and 16-bit values (16-bit floats too) in storage buffers, uniform buffers
        // and push constants: translate_narrow.cpp (shaderInt8, shaderInt16, the 8/16-bit storage features).
        // Not StorageInputOutput16 (lavapipe does not report it) nor Float16 (half arithmetic).
        case spv::Capability::Int8:
        case spv::Capability::Int16:
        case spv::Capability::StorageBuffer16BitAccess:
        case spv::Capability::UniformAndStorageBuffer16BitAccess:
        case spv::Capability::StoragePushConstant16:
        case spv::Capability::StorageBuffer8BitAccess:
        case spv::Capability::UniformAndStorageBuffer8BitAccess:
        case spv::Capability::StoragePushConstant8:
        // OpAtomicFAddEXT and OpAtomicFMinEXT / FMaxEXT on 32-bit floats in buffers, images and Workgroup memory
        // (translate_atomic.cpp; VK_EXT_shader_atomic_float, VK_EXT_shader_atomic_float2). Not the 16- and 64-bit
        // float forms, which lavapipe does not report either.
        case spv::Capability::AtomicFloat32AddEXT:
        case spv::Capability::AtomicFloat32MinMaxEXT:
        // 64-bit integer atomics on storage buffers and Workgroup memory (VK_KHR_shader_atomic_int64).
        case spv::Capability::Int64Atomics:
            return true;
        default:
            return false;
    }
}

bool extension_supported(const std::string& e) {
    return e == "SPV_KHR_shader_draw_parameters" || e == "SPV_KHR_multiview" ||
           e == "SPV_EXT_demote_to_helper_invocation" || e == "SPV_KHR_storage_buffer_storage_class" ||
           e == "SPV_EXT_descriptor_indexing" || e == "SPV_KHR_non_semantic_info" ||
           e == "SPV_KHR_terminate_invocation" || e == "SPV_KHR_integer_dot_product" ||
           e == "SPV_KHR_vulkan_memory_model" || e == "SPV_KHR_physical_storage_buffer" ||
           e == "SPV_EXT_physical_storage_buffer" || e == "SPV_KHR_16bit_storage" || e == "SPV_KHR_8bit_storage" ||
           e == "SPV_EXT_shader_atomic_float_add" || e == "SPV_EXT_shader_atomic_float_min_max" ||
           // OpDecorateString / OpDecorateId with UserSemantic, HlslCounterBufferGOOGLE: reflection only, ignored
           e == "SPV_GOOGLE_decorate_string" || e == "SPV_GOOGLE_hlsl_functionality1";
}

}  // namespace

void Translator::declare(const Instr& in) {
    switch (in.op) {
        case spv::Op::OpCapability:
            if (!capability_supported(spv::Capability(in[1])))
                fail(std::string("unsupported capability ") + names::capability(in[1]));
            return;
        case spv::Op::OpExtension:
            if (!extension_supported(literal_string(in, 1))) fail("unsupported extension " + literal_string(in, 1));
            return;
        case spv::Op::OpExtInstImport:
            if (literal_string(in, 2) == "GLSL.std.450")
                glsl_ext_ = in[1];
            else if (literal_string(in, 2).rfind("NonSemantic.", 0) != 0)
                fail("unsupported extended instruction set " + literal_string(in, 2));
            return;
        case spv::Op::OpMemoryModel:
            if (spv::AddressingModel(in[1]) != spv::AddressingModel::Logical &&
                spv::AddressingModel(in[1]) != spv::AddressingModel::PhysicalStorageBuffer64)
                fail("unsupported addressing model (only Logical and PhysicalStorageBuffer64)");
            return;
        case spv::Op::OpExecutionMode:
        case spv::Op::OpExecutionModeId:
            if (in[1] == entry_fn_) declare_execution_mode(in);
            return;
        case spv::Op::OpDecorate:
        case spv::Op::OpMemberDecorate:
            return decorate(in);
        case spv::Op::OpConstant:
        case spv::Op::OpConstantTrue:
        case spv::Op::OpConstantFalse:
        case spv::Op::OpConstantNull:
        case spv::Op::OpUndef:
        case spv::Op::OpConstantComposite:
            return declare_constant(in);
        case spv::Op::OpSpecConstant:
        case spv::Op::OpSpecConstantTrue:
        case spv::Op::OpSpecConstantFalse:
        case spv::Op::OpSpecConstantComposite:
        case spv::Op::OpSpecConstantOp:
            fail("specialization constant left unresolved (" + std::string(names::opcode(uint32_t(in.op))) + ")");
        case spv::Op::OpVariable:
            return declare_variable(in);
        default:
            if (in.op >= spv::Op::OpTypeVoid && in.op <= spv::Op::OpTypeForwardPointer) return declare_type(in);
            return;
    }
}

void Translator::declare_execution_mode(const Instr& in) {
    switch (spv::ExecutionMode(in[2])) {
        case spv::ExecutionMode::OriginUpperLeft:
            iface_.origin_upper_left = true;
            return;
        case spv::ExecutionMode::EarlyFragmentTests:
            iface_.early_fragment_tests = true;
            return;
        case spv::ExecutionMode::DepthReplacing:
            iface_.depth_replacing = true;
            return;
        case spv::ExecutionMode::DepthGreater:
        case spv::ExecutionMode::DepthLess:
        case spv::ExecutionMode::DepthUnchanged:
        case spv::ExecutionMode::LocalSizeHint:
        case spv::ExecutionMode::LocalSizeHintId:  // SPIR-V 1.2+: the hint with ids, a hint all the same
            return;
        case spv::ExecutionMode::LocalSize:
            if (in.n < 6) fail("invalid SPIR-V: LocalSize needs three sizes");
            if (!workgroup_size_builtin_) iface_.local_size = {in[3], in[4], in[5]};
            return;
        case spv::ExecutionMode::LocalSizeId:
            if (in.n < 6) fail("invalid SPIR-V: LocalSizeId needs three ids");
            for (int i = 0; i < 3; ++i) local_size_ids_[i] = in[3 + i];
            return;
        default:
            fail(std::string("unsupported execution mode ") + names::execution_mode(in[2]));
    }
}

void Translator::decorate(const Instr& in) {
    bool member = in.op == spv::Op::OpMemberDecorate;
    if (in[1] >= bound_) fail("invalid SPIR-V: decoration target out of range");
    Decorations& d = member ? member_deco_[{in[1], in[2]}] : deco_[in[1]];
    size_t a = member ? 3 : 2;
    uint32_t arg = in.n > a + 1 ? in[a + 1] : 0;
    switch (spv::Decoration(in[a])) {
        case spv::Decoration::Location:
            d.location = int(arg);
            return;
        case spv::Decoration::Component:
            d.component = int(arg);
            return;
        case spv::Decoration::BuiltIn:
            d.builtin = int(arg);
            return;
        case spv::Decoration::Flat:
            d.flat = true;
            return;
        case spv::Decoration::NoPerspective:
            d.noperspective = true;
            return;
        case spv::Decoration::Centroid:
            d.centroid = true;
            return;
        case spv::Decoration::Sample:
            d.sample = true;
            return;
        case spv::Decoration::DescriptorSet:
            d.set = int(arg);
            return;
        case spv::Decoration::Binding:
            d.binding = int(arg);
            return;
        case spv::Decoration::Offset:
            d.offset = int(arg);
            return;
        case spv::Decoration::ArrayStride:
            d.array_stride = int(arg);
            return;
        case spv::Decoration::MatrixStride:
            d.matrix_stride = int(arg);
            return;
        case spv::Decoration::RowMajor:
            d.row_major = true;
            return;
        case spv::Decoration::Block:
            d.block = true;
            return;
        case spv::Decoration::BufferBlock:
            d.buffer_block = true;
            return;
        case spv::Decoration::NonWritable:
            d.non_writable = true;
            return;
        case spv::Decoration::Index:
            if (arg > 1) fail("decoration Index " + std::to_string(arg) + " (only 0 and 1 exist)");
            d.index = int(arg);
            return;
        case spv::Decoration::PerPrimitiveNV:
        case spv::Decoration::PerVertexKHR:
            fail(std::string("unsupported decoration ") + names::decoration(in[a]));
        default:
            return;  // RelaxedPrecision, NoContraction, Invariant, ... do not change results here
    }
}

void Translator::declare_type(const Instr& in) {
    Type& t = types_[in[1]];
    switch (in.op) {
        case spv::Op::OpTypeVoid:
            t.kind = Type::Void;
            break;
        case spv::Op::OpTypeBool:
            t = Type{}, t.kind = Type::Bool;
            t.flat = 1;
            break;
        case spv::Op::OpTypeInt:
        case spv::Op::OpTypeFloat:
            // 64-bit integers and doubles: two registers, low word first (translate_wide.cpp); 8- and 16-bit
            // integers and 16-bit floats: one register, zero-extended (translate_narrow.cpp)
            if (in[2] != 32 && in[2] != 64 && in[2] != 16 && !(in[2] == 8 && in.op == spv::Op::OpTypeInt))
                fail(std::string(in.op == spv::Op::OpTypeInt ? "int" : "float") + std::to_string(in[2]) +
                     " types are not supported");
            t.kind = in.op == spv::Op::OpTypeInt ? Type::Int : Type::Float;
            t.is_signed = in.op == spv::Op::OpTypeInt && in[3];
            t.wide = in[2] == 64;
            t.bits = std::min(in[2], 32u);
            t.flat = t.wide ? 2 : 1;
            break;
        case spv::Op::OpTypeVector:
        case spv::Op::OpTypeMatrix:
        case spv::Op::OpTypeArray:
        case spv::Op::OpTypeRuntimeArray:
            declare_composite_type(in, t);
            break;
        case spv::Op::OpTypeStruct: {
            t.kind = Type::Struct;
            uint64_t flat = 0;
            for (size_t m = 2; m < in.n; ++m) {
                t.members.push_back(in[m]);
                flat += type(in[m]).flat;
            }
            if (flat > (1u << 20)) fail("struct type too large");
            t.flat = uint32_t(flat);
            break;
        }
        case spv::Op::OpTypePointer:
            t = Type{}, t.kind = Type::Pointer;
            t.storage = spv::StorageClass(in[2]);
            t.elem = in[3];
            // a PhysicalStorageBuffer pointer is a value: its 64-bit address in two registers
            if (t.storage == spv::StorageClass::PhysicalStorageBuffer) t.flat = 2;
            break;
        case spv::Op::OpTypeForwardPointer:  // structs may hold it before its OpTypePointer: its size now
            t = Type{}, t.kind = Type::Pointer;
            t.storage = spv::StorageClass(in[2]);
            if (t.storage == spv::StorageClass::PhysicalStorageBuffer) t.flat = 2;
            break;
        case spv::Op::OpTypeFunction:
            t.kind = Type::Function;
            break;
        case spv::Op::OpTypeImage:
            declare_image_type(in, t);
            break;
        case spv::Op::OpTypeSampler:
            t = Type{}, t.kind = Type::Sampler;
            t.flat = 1;
            break;
        case spv::Op::OpTypeSampledImage:
            t = Type{}, t.kind = Type::SampledImage;
            t.elem = in[2];
            t.flat = 1;
            break;
        default:
            return;  // OpenCL-only types: a module using them does not validate for Vulkan
    }
    is_type_[in[1]] = 1;
}

void Translator::declare_composite_type(const Instr& in, Type& t) {
    t.kind = in.op == spv::Op::OpTypeVector   ? Type::Vector
             : in.op == spv::Op::OpTypeMatrix ? Type::Matrix
             : in.op == spv::Op::OpTypeArray  ? Type::Array
                                              : Type::RuntimeArray;
    t.elem = in[2];
    if (in.op == spv::Op::OpTypeArray) {
        uint32_t v = 0;
        if (!const_of(in[3], v)) fail("array length is not a constant");
        if (v == 0 || v > (1u << 20)) fail("unsupported array length " + std::to_string(v));
        t.count = v;
    } else if (in.op != spv::Op::OpTypeRuntimeArray) {
        t.count = in[3];
    }
    uint64_t flat = uint64_t(type(t.elem).flat) * t.count;
    if (flat > (1u << 20)) fail("composite type too large");
    t.flat = uint32_t(flat);
}

void Translator::declare_image_type(const Instr& in, Type& t) {
    t.kind = Type::Image;
    t.elem = in[2];
    t.dim = in[3];
    t.arrayed = in[5];
    t.ms = in[6];
    t.sampled = in[7];
    t.flat = 1;
    // Multisampled images are sampled images only (sampler2DMS[Array]: texelFetch with a sample index and
    // textureSamples, translate_image.cpp); storage images and input attachments with samples are not supported
    // (shaderStorageImageMultisample is off; 4x images cannot have STORAGE or INPUT_ATTACHMENT usage).
    if (t.ms && (t.sampled == 2 || spv::Dim(t.dim) != spv::Dim::Dim2D))
        fail(spv::Dim(t.dim) == spv::Dim::SubpassData
                 ? "multisampled input attachment (subpassInputMS) is not supported"
                 : "multisampled storage image (shaderStorageImageMultisample) or multisampled image that is not 2D");
    if (spv::Dim(t.dim) == spv::Dim::SubpassData) {
        // Input attachment (read by OpImageRead only): needs the fragment's pixel, copied in from gl_FragCoord
        // into two hidden local words.
        if (stage_ != Stage::Fragment) fail("input attachment outside a fragment shader");
        if (subpass_coord_word_ == kNoReg) {
            subpass_coord_word_ = local_words_;
            local_words_ += 2;
            p_.io_in.push_back(IoCopy{IoSlot::FragCoord, 0, subpass_coord_word_});
            p_.io_in.push_back(IoCopy{IoSlot::FragCoord, 1, subpass_coord_word_ + 1});
            iface_.builtins_read |= bit(BuiltIn::FragCoord);
        }
        return;
    }
    if (spv::Dim(t.dim) == spv::Dim::Buffer) {
        // Texel buffers: one row of one level (the icd binds the buffer view as one); uniform ones are fetched
        // like a 1D image, storage ones (imageBuffer) read, written and used by atomics as a 2D storage image at
        // y = 0 (translate_image.cpp).
        if (t.arrayed) fail("invalid arrayed texel buffer");
        return;
    }
    if (spv::Dim(t.dim) == spv::Dim::Cube) {
        // samplerCube[Array][Shadow]: sampled through texture_cube.cpp; storage cube images are not implemented
        if (t.sampled == 2) fail("unsupported storage image dimension Cube (imageCube / imageCubeArray)");
        return;
    }
    const bool dim_3d = spv::Dim(t.dim) == spv::Dim::Dim3D;
    if (spv::Dim(t.dim) != spv::Dim::Dim2D && spv::Dim(t.dim) != spv::Dim::Dim1D && !dim_3d) {
        const char* name = spv::Dim(t.dim) == spv::Dim::Rect ? "Rect" : "this dimension";
        fail(std::string("unsupported image dimension ") + name +
             " (only 1D, 2D, 3D and Cube, 1D, 2D and Cube arrays included)");
    }
    if (dim_3d && t.arrayed) fail("invalid arrayed 3D image");
    // Storage images (imageLoad / imageStore / imageSize): 2D and 2D arrays. image3D is not implemented, and icd/
    // refuses STORAGE usage on 3D images (physical_device.cpp).
    if (t.sampled == 2 && spv::Dim(t.dim) != spv::Dim::Dim2D)
        fail(dim_3d ? "unsupported storage image dimension Dim3D (image3D; only 2D, arrays included)"
                    : "unsupported storage image dimension (only 2D, arrays included)");
}

void Translator::declare_constant(const Instr& in) {
    switch (in.op) {
        case spv::Op::OpConstant: {
            const Type& t = type(in[1]);
            if (t.kind != Type::Int && t.kind != Type::Float) fail("unsupported constant type");
            if (t.wide) {  // low word, high word
                const uint32_t r = alloc(2);
                set_const(r, in[3]);
                set_const(r + 1, in.n > 4 ? in[4] : 0);
                vals_[in[2]] = Value{r, in[1]};
                return;
            }
            // a narrow literal's word is sign-extended for signed types: kept zero-extended here
            vals_[in[2]] = Value{konst(t.bits < 32 ? in[3] & ((1u << t.bits) - 1) : in[3]), in[1]};
            return;
        }
        case spv::Op::OpConstantTrue:
        case spv::Op::OpConstantFalse:
            vals_[in[2]] = Value{konst(in.op == spv::Op::OpConstantTrue ? ~0u : 0u), in[1]};
            return;
        default:
            break;
    }
    // OpConstantNull, OpUndef, OpConstantComposite: a run of constant registers.
    const Type& t = type(in[1]);
    uint32_t base = alloc(std::max(1u, t.flat));
    if (in.op == spv::Op::OpConstantComposite) {
        uint32_t at = 0;
        for (size_t m = 3; m < in.n; ++m) {
            const Value& c = val(in[m]);
            uint32_t f = type(c.type).flat;
            for (uint32_t j = 0; j < f; ++j) {
                // constant registers are initialized once; copy their values
                auto it = reg_value_.find(c.reg + j);
                set_const(base + at + j, it != reg_value_.end() ? it->second : 0);
            }
            at += f;
        }
    } else {
        for (uint32_t j = 0; j < t.flat; ++j) set_const(base + j, 0);
    }
    vals_[in[2]] = Value{base, in[1]};
    // The WorkgroupSize built-in (a constant, specialized by now) overrides LocalSize and LocalSizeId.
    if (deco_[in[2]].builtin == int(spv::BuiltIn::WorkgroupSize)) {
        if (t.kind != Type::Vector || t.count != 3 || t.flat != 3) fail("WorkgroupSize is not a 3-component vector");
        for (uint32_t j = 0; j < 3; ++j) iface_.local_size[j] = reg_value_[base + j];
        workgroup_size_builtin_ = true;
    }
}

void Translator::resolve_local_size() {
    if (workgroup_size_builtin_ || local_size_ids_[0] == 0) return;
    for (int i = 0; i < 3; ++i) {
        uint32_t v = 0;
        if (!const_of(local_size_ids_[i], v)) fail("LocalSizeId operand is not a constant");
        iface_.local_size[i] = v;
    }
}

}  // namespace tilevk::shader
