// SPIR-V module -> SIMD program: types, constants, interface variables, and structured control flow as masks.
//
// Control flow: blocks are laid out in a structured reverse post-order (a loop's or selection's merge block is
// visited first, so it lands after the construct's body). Every block has a mask register of the lanes that
// reached it; a branch ORs (mask & condition) into its targets' masks and a phi is a masked move on each edge.
// A block whose mask is empty is skipped. A loop's back edge ORs into the header mask and jumps back while any
// lane is set. Return and kill simply send lanes nowhere.
#include <algorithm>
#include <bit>
#include <cstring>
#include <functional>

#include <spirv/unified1/GLSL.std.450.h>

#include "shader/spirv_names.h"
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

uint32_t Translator::konst(uint32_t v) {
    auto it = const_regs_.find(v);
    if (it != const_regs_.end()) return it->second;
    uint32_t r = alloc();
    set_const(r, v);
    const_regs_[v] = r;
    return r;
}
uint32_t Translator::konstf(float f) {
    return konst(std::bit_cast<uint32_t>(f));
}

const Type& Translator::type(uint32_t id) const {
    if (id >= bound_ || !is_type_[id]) fail("invalid type id " + std::to_string(id));
    return types_[id];
}
Value& Translator::val(uint32_t id) {
    if (id >= bound_ || (vals_[id].reg == kNoReg && vals_[id].ptr < 0))
        fail("use of unsupported or undefined value %" + std::to_string(id));
    return vals_[id];
}
uint32_t Translator::component_type(uint32_t t) const {
    while (types_[t].kind == Type::Vector || types_[t].kind == Type::Matrix) t = types_[t].elem;
    return t;
}

// Flat register offset of a composite index path (OpCompositeExtract/Insert literals).
uint32_t Translator::flat_index(uint32_t t, const uint32_t* idx, size_t n, uint32_t* out_type) const {
    uint32_t off = 0;
    for (size_t i = 0; i < n; ++i) {
        const Type& ty = type(t);
        uint32_t k = idx[i];
        switch (ty.kind) {
            case Type::Vector:
            case Type::Matrix:
            case Type::Array:
                if (k >= ty.count) fail("composite index out of range");
                off += k * type(ty.elem).flat;
                t = ty.elem;
                break;
            case Type::Struct:
                if (k >= ty.members.size()) fail("composite index out of range");
                for (uint32_t m = 0; m < k; ++m) off += type(ty.members[m]).flat;
                t = ty.members[k];
                break;
            default:
                fail("composite index into a non-composite");
        }
    }
    *out_type = t;
    return off;
}

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
        case spv::BuiltIn::HelperInvocation:
            return bit(BuiltIn::HelperInvocation);
        default:
            return 0;
    }
}

// Which IoSlot a builtin maps to, given the stage and direction; fails for anything unsupported.
IoSlot builtin_slot(spv::BuiltIn b, Stage stage, bool output) {
    std::string where = std::string(stage == Stage::Vertex ? "vertex " : "fragment ") + (output ? "output" : "input");
    if (stage == Stage::Vertex && !output) {
        if (b == spv::BuiltIn::VertexIndex) return IoSlot::VertexIndex;
        if (b == spv::BuiltIn::InstanceIndex) return IoSlot::InstanceIndex;
        if (b == spv::BuiltIn::BaseVertex) return IoSlot::BaseVertex;
        if (b == spv::BuiltIn::BaseInstance) return IoSlot::BaseInstance;
        if (b == spv::BuiltIn::DrawIndex) return IoSlot::DrawIndex;
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
        if (b == spv::BuiltIn::HelperInvocation) return IoSlot::HelperInvocation;
    } else {
        if (b == spv::BuiltIn::FragDepth) return IoSlot::FragDepth;
        if (b == spv::BuiltIn::SampleMask) return IoSlot::SampleMask;
    }
    Translator::fail(std::string("unsupported builtin ") + names::builtin(uint32_t(b)) + " as " + where);
}

bool capability_supported(spv::Capability c) {
    switch (c) {
        case spv::Capability::Shader:
        case spv::Capability::Matrix:
        case spv::Capability::ClipDistance:
        case spv::Capability::CullDistance:
        case spv::Capability::DerivativeControl:
        case spv::Capability::DrawParameters:
        case spv::Capability::ImageQuery:
        case spv::Capability::SampleRateShading:
        case spv::Capability::DemoteToHelperInvocation:
        case spv::Capability::Sampled1D:
        case spv::Capability::InputAttachment:  // subpassLoad: a texel fetch at the fragment's pixel
        case spv::Capability::SampledBuffer:    // uniform texel buffers: texelFetch / textureSize only
        case spv::Capability::StorageImageExtendedFormats:
        case spv::Capability::InterpolationFunction:  // its three instructions fail by name in translate_glsl
        case spv::Capability::ShaderNonUniform:
        case spv::Capability::SampledImageArrayDynamicIndexing:
        case spv::Capability::UniformBufferArrayDynamicIndexing:
        case spv::Capability::StorageBufferArrayDynamicIndexing:
            return true;
        default:
            return false;
    }
}

}  // namespace

void Translator::run(const std::vector<uint32_t>& words, std::string_view entry_name) {
    if (words.size() < 5) fail("invalid SPIR-V: no header");
    bound_ = words[3];
    if (bound_ > (1u << 22)) fail("SPIR-V id bound too large");
    types_.resize(bound_);
    is_type_.assign(bound_, 0);
    deco_.resize(bound_);
    vals_.resize(bound_);
    iface_.stage = stage_;
    iface_.entry = std::string(entry_name);
    p_.stage = stage_;

    std::vector<Instr> ins;
    for (size_t i = 5; i < words.size();) {
        uint32_t n = words[i] >> 16;
        if (n == 0 || i + n > words.size()) fail("invalid SPIR-V: truncated instruction");
        ins.push_back(Instr{spv::Op(words[i] & 0xffff), &words[i], n});
        i += n;
    }
    auto str = [](const Instr& in, size_t at) {
        return std::string(reinterpret_cast<const char*>(in.w + at),
                           strnlen(reinterpret_cast<const char*>(in.w + at), (in.n - at) * 4));
    };

    // Fixed registers: constant zero, the entry mask and the live mask (filled by the executor).
    zero_ = konst(0);
    p_.reg_entry_mask = alloc();
    p_.reg_live = alloc();

    uint32_t entry_fn = 0;
    std::vector<uint32_t> entry_iface;
    spv::ExecutionModel want = stage_ == Stage::Vertex ? spv::ExecutionModel::Vertex : spv::ExecutionModel::Fragment;
    for (const Instr& in : ins) {
        if (in.op == spv::Op::OpEntryPoint && spv::ExecutionModel(in[1]) == want && str(in, 3) == entry_name) {
            entry_fn = in[2];
            size_t name_words = (str(in, 3).size() + 4) / 4;
            for (size_t k = 3 + name_words; k < in.n; ++k) entry_iface.push_back(in[k]);
        }
    }
    if (!entry_fn)
        fail("no " + std::string(stage_ == Stage::Vertex ? "vertex" : "fragment") + " entry point named '" +
             std::string(entry_name) + "'");

    // Pass 1: module-level declarations.
    size_t fn_begin = ins.size();
    uint32_t local_words = 0;
    uint32_t next_slot = 1;  // slot 0: push constants
    for (size_t k = 0; k < ins.size(); ++k) {
        const Instr& in = ins[k];
        switch (in.op) {
            case spv::Op::OpCapability:
                if (!capability_supported(spv::Capability(in[1])))
                    fail(std::string("unsupported capability ") + names::capability(in[1]));
                break;
            case spv::Op::OpExtension: {
                std::string e = str(in, 1);
                if (e != "SPV_KHR_shader_draw_parameters" && e != "SPV_EXT_demote_to_helper_invocation" &&
                    e != "SPV_KHR_storage_buffer_storage_class" && e != "SPV_EXT_descriptor_indexing" &&
                    e != "SPV_KHR_non_semantic_info")
                    fail("unsupported extension " + e);
                break;
            }
            case spv::Op::OpExtInstImport:
                if (str(in, 2) == "GLSL.std.450")
                    glsl_ext_ = in[1];
                else if (str(in, 2).rfind("NonSemantic.", 0) != 0)
                    fail("unsupported extended instruction set " + str(in, 2));
                break;
            case spv::Op::OpMemoryModel:
                if (spv::AddressingModel(in[1]) != spv::AddressingModel::Logical)
                    fail("unsupported addressing model (only Logical)");
                break;
            case spv::Op::OpExecutionMode:
            case spv::Op::OpExecutionModeId:
                if (in[1] != entry_fn) break;
                switch (spv::ExecutionMode(in[2])) {
                    case spv::ExecutionMode::OriginUpperLeft:
                        iface_.origin_upper_left = true;
                        break;
                    case spv::ExecutionMode::EarlyFragmentTests:
                        iface_.early_fragment_tests = true;
                        break;
                    case spv::ExecutionMode::DepthReplacing:
                        iface_.depth_replacing = true;
                        break;
                    case spv::ExecutionMode::DepthGreater:
                    case spv::ExecutionMode::DepthLess:
                    case spv::ExecutionMode::DepthUnchanged:
                        break;
                    default:
                        fail(std::string("unsupported execution mode ") + names::execution_mode(in[2]));
                }
                break;
            case spv::Op::OpDecorate:
            case spv::Op::OpMemberDecorate: {
                bool member = in.op == spv::Op::OpMemberDecorate;
                if (in[1] >= bound_) fail("invalid SPIR-V: decoration target out of range");
                Decorations& d = member ? member_deco_[{in[1], in[2]}] : deco_[in[1]];
                size_t a = member ? 3 : 2;
                uint32_t arg = in.n > a + 1 ? in[a + 1] : 0;
                switch (spv::Decoration(in[a])) {
                    case spv::Decoration::Location:
                        d.location = int(arg);
                        break;
                    case spv::Decoration::Component:
                        d.component = int(arg);
                        break;
                    case spv::Decoration::BuiltIn:
                        d.builtin = int(arg);
                        break;
                    case spv::Decoration::Flat:
                        d.flat = true;
                        break;
                    case spv::Decoration::NoPerspective:
                        d.noperspective = true;
                        break;
                    case spv::Decoration::Centroid:
                        d.centroid = true;
                        break;
                    case spv::Decoration::Sample:
                        d.sample = true;
                        break;
                    case spv::Decoration::DescriptorSet:
                        d.set = int(arg);
                        break;
                    case spv::Decoration::Binding:
                        d.binding = int(arg);
                        break;
                    case spv::Decoration::Offset:
                        d.offset = int(arg);
                        break;
                    case spv::Decoration::ArrayStride:
                        d.array_stride = int(arg);
                        break;
                    case spv::Decoration::MatrixStride:
                        d.matrix_stride = int(arg);
                        break;
                    case spv::Decoration::RowMajor:
                        d.row_major = true;
                        break;
                    case spv::Decoration::Block:
                        d.block = true;
                        break;
                    case spv::Decoration::BufferBlock:
                        d.buffer_block = true;
                        break;
                    case spv::Decoration::NonWritable:
                        d.non_writable = true;
                        break;
                    case spv::Decoration::Index:
                        if (arg != 0) fail("unsupported decoration Index (dual-source blending)");
                        break;
                    case spv::Decoration::PerPrimitiveNV:
                    case spv::Decoration::PerVertexKHR:
                        fail(std::string("unsupported decoration ") + names::decoration(in[a]));
                    default:
                        break;  // RelaxedPrecision, NoContraction, Invariant, ... do not change results here
                }
                break;
            }
            case spv::Op::OpTypeVoid:
                types_[in[1]].kind = Type::Void;
                is_type_[in[1]] = 1;
                break;
            case spv::Op::OpTypeBool:
                types_[in[1]] = Type{}, types_[in[1]].kind = Type::Bool;
                types_[in[1]].flat = 1;
                is_type_[in[1]] = 1;
                break;
            case spv::Op::OpTypeInt:
            case spv::Op::OpTypeFloat: {
                if (in[2] != 32)
                    fail(std::string(in.op == spv::Op::OpTypeInt ? "int" : "float") + std::to_string(in[2]) +
                         " types are not supported (32-bit only)");
                Type& t = types_[in[1]];
                t.kind = in.op == spv::Op::OpTypeInt ? Type::Int : Type::Float;
                t.is_signed = in.op == spv::Op::OpTypeInt && in[3];
                t.flat = 1;
                is_type_[in[1]] = 1;
                break;
            }
            case spv::Op::OpTypeVector:
            case spv::Op::OpTypeMatrix:
            case spv::Op::OpTypeArray:
            case spv::Op::OpTypeRuntimeArray: {
                Type& t = types_[in[1]];
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
                is_type_[in[1]] = 1;
                break;
            }
            case spv::Op::OpTypeStruct: {
                Type& t = types_[in[1]];
                t.kind = Type::Struct;
                uint64_t flat = 0;
                for (size_t m = 2; m < in.n; ++m) {
                    t.members.push_back(in[m]);
                    flat += type(in[m]).flat;
                }
                if (flat > (1u << 20)) fail("struct type too large");
                t.flat = uint32_t(flat);
                is_type_[in[1]] = 1;
                break;
            }
            case spv::Op::OpTypePointer:
                types_[in[1]] = Type{}, types_[in[1]].kind = Type::Pointer;
                types_[in[1]].storage = spv::StorageClass(in[2]);
                types_[in[1]].elem = in[3];
                is_type_[in[1]] = 1;
                break;
            case spv::Op::OpTypeFunction:
                types_[in[1]].kind = Type::Function;
                is_type_[in[1]] = 1;
                break;
            case spv::Op::OpTypeImage: {
                Type& t = types_[in[1]];
                t.kind = Type::Image;
                t.elem = in[2];
                t.dim = in[3];
                t.arrayed = in[5];
                t.ms = in[6];
                t.sampled = in[7];
                t.flat = 1;
                is_type_[in[1]] = 1;
                if (t.ms) fail("unsupported multisampled image type");
                if (spv::Dim(t.dim) == spv::Dim::SubpassData) {
                    // Input attachment (read by OpImageRead only): needs the fragment's pixel, copied in from
                    // gl_FragCoord into two hidden local words.
                    if (stage_ != Stage::Fragment) fail("input attachment outside a fragment shader");
                    if (subpass_coord_word_ == kNoReg) {
                        subpass_coord_word_ = local_words;
                        local_words += 2;
                        p_.io_in.push_back(IoCopy{IoSlot::FragCoord, 0, subpass_coord_word_});
                        p_.io_in.push_back(IoCopy{IoSlot::FragCoord, 1, subpass_coord_word_ + 1});
                        iface_.builtins_read |= bit(BuiltIn::FragCoord);
                    }
                    break;
                }
                if (spv::Dim(t.dim) == spv::Dim::Buffer) {
                    // Uniform texel buffer: fetched like a 1D image of one level (the icd binds the buffer view
                    // as one); storage texel buffers (imageLoad/imageStore) are not implemented.
                    if (t.sampled == 2) fail("unsupported storage texel buffer (imageBuffer)");
                    if (t.arrayed) fail("invalid arrayed texel buffer");
                    break;
                }
                if (spv::Dim(t.dim) != spv::Dim::Dim2D && spv::Dim(t.dim) != spv::Dim::Dim1D)
                    fail("unsupported image dimension (only 1D and 2D, arrays included)");
                if (t.sampled == 2) fail("unsupported storage image (imageLoad/imageStore)");
                break;
            }
            case spv::Op::OpTypeSampler:
                types_[in[1]] = Type{}, types_[in[1]].kind = Type::Sampler;
                types_[in[1]].flat = 1;
                is_type_[in[1]] = 1;
                break;
            case spv::Op::OpTypeSampledImage:
                types_[in[1]] = Type{}, types_[in[1]].kind = Type::SampledImage;
                types_[in[1]].elem = in[2];
                types_[in[1]].flat = 1;
                is_type_[in[1]] = 1;
                break;
            case spv::Op::OpConstant: {
                const Type& t = type(in[1]);
                if (t.kind != Type::Int && t.kind != Type::Float) fail("unsupported constant type");
                vals_[in[2]] = Value{konst(in[3]), in[1]};
                break;
            }
            case spv::Op::OpConstantTrue:
            case spv::Op::OpConstantFalse:
                vals_[in[2]] = Value{konst(in.op == spv::Op::OpConstantTrue ? ~0u : 0u), in[1]};
                break;
            case spv::Op::OpConstantNull:
            case spv::Op::OpUndef:
            case spv::Op::OpConstantComposite: {
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
                break;
            }
            case spv::Op::OpSpecConstant:
            case spv::Op::OpSpecConstantTrue:
            case spv::Op::OpSpecConstantFalse:
            case spv::Op::OpSpecConstantComposite:
            case spv::Op::OpSpecConstantOp:
                fail("specialization constant left unresolved (" + std::string(names::opcode(uint32_t(in.op))) + ")");
            case spv::Op::OpVariable: {
                const Type& pt = type(in[1]);
                spv::StorageClass sc = spv::StorageClass(in[3]);
                uint32_t id = in[2];
                const Type& t = type(pt.elem);
                Pointer p;
                p.type = pt.elem;
                const Decorations& d = deco_[id];
                switch (sc) {
                    case spv::StorageClass::Private:
                    case spv::StorageClass::Input:
                    case spv::StorageClass::Output: {
                        p.space = Space::Local;
                        p.base = local_words;
                        p.limit = local_words + t.flat;
                        local_words += t.flat;
                        if (in.n > 4) private_inits_.push_back({uint32_t(pointers_.size()), in[4]});
                        if (sc != spv::StorageClass::Private &&
                            std::find(entry_iface.begin(), entry_iface.end(), id) != entry_iface.end()) {
                            // interface variable: record copies in/out
                            bool out = sc == spv::StorageClass::Output;
                            std::function<void(uint32_t, uint32_t, int, int, const Decorations&, int)> walk;
                            walk = [&](uint32_t ty, uint32_t word, int loc, int comp, const Decorations& dd,
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
                                    if ((s == IoSlot::ClipDistance || s == IoSlot::CullDistance) &&
                                        n > kMaxClipDistances)
                                        fail("too many clip/cull distances");
                                    for (uint32_t j = 0; j < n; ++j)
                                        (out ? p_.io_out : p_.io_in).push_back(IoCopy{s, j, word + j});
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
                                        walk(tt.members[m], w, l, md.component, md, md.builtin);
                                        uint32_t mt = tt.members[m];
                                        uint32_t locs = type(mt).kind == Type::Array
                                                            ? type(mt).count * (type(type(mt).elem).kind == Type::Matrix
                                                                                    ? type(type(mt).elem).count
                                                                                    : 1)
                                                        : type(mt).kind == Type::Matrix ? type(mt).count
                                                                                        : 1;
                                        if (md.builtin < 0) l += int(locs);
                                        w += type(mt).flat;
                                    }
                                    return;
                                }
                                if (tt.kind == Type::Array || tt.kind == Type::Matrix) {
                                    uint32_t ef = type(tt.elem).flat;
                                    uint32_t el = type(tt.elem).kind == Type::Matrix ? type(tt.elem).count : 1;
                                    for (uint32_t i = 0; i < tt.count; ++i)
                                        walk(tt.elem, word + i * ef, loc + int(i * el), comp, dd, -1);
                                    return;
                                }
                                if (loc < 0) fail("interface variable without a location");
                                uint32_t n = tt.flat;
                                if (n > 4 || comp + n > 4) fail("interface variable wider than 4 components");
                                int maxloc = out && stage_ == Stage::Fragment ? kMaxColorOutputs : kMaxLocations;
                                if (loc >= maxloc) fail("location " + std::to_string(loc) + " out of range");
                                for (uint32_t j = 0; j < n; ++j)
                                    (out ? p_.io_out : p_.io_in)
                                        .push_back(IoCopy{out ? IoSlot::Output : IoSlot::Input,
                                                          uint32_t(loc * 4 + comp + int(j)), word + j});
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
                            };
                            walk(pt.elem, p.base, d.location, d.component, d, d.builtin);
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
                    case spv::StorageClass::UniformConstant: {
                        if (d.set < 0 || d.binding < 0) fail("resource variable without DescriptorSet/Binding");
                        uint32_t count = 1;
                        uint32_t inner = pt.elem;
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
                                use.kind = DescriptorKind::SampledImage;
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
                        p.base = next_slot;
                        p.limit = count;
                        p_.slots.push_back(SlotBinding{use.set, use.binding, count});
                        next_slot += count;
                        if (next_slot > (1u << 15)) fail("too many descriptors");
                        iface_.descriptors.push_back(use);
                        break;
                    }
                    case spv::StorageClass::Function:
                        fail("function variable at module scope");
                    default:
                        fail(std::string("unsupported storage class ") + names::storage_class(in[3]));
                }
                pointers_.push_back(p);
                vals_[id] = Value{kNoReg, in[1], int(pointers_.size() - 1)};
                break;
            }
            case spv::Op::OpFunction:
                fn_begin = std::min(fn_begin, k);
                break;
            default:
                break;
        }
        if (in.op == spv::Op::OpFunction) break;
    }
    p_.num_slots = next_slot;
    if (local_words > (1u << 20)) fail("too much variable memory");

    // The function: after inlining only the entry point should remain.
    size_t fb = fn_begin;
    if (fb >= ins.size() || ins[fb][2] != entry_fn) {
        for (; fb < ins.size(); ++fb)
            if (ins[fb].op == spv::Op::OpFunction && ins[fb][2] == entry_fn) break;
    }
    if (fb >= ins.size()) fail("entry point function not found");
    std::vector<Block> blocks;
    std::unordered_map<uint32_t, uint32_t> block_of;  // label -> index
    size_t k = fb + 1;
    for (; k < ins.size() && ins[k].op != spv::Op::OpFunctionEnd; ++k) {
        const Instr& in = ins[k];
        if (in.op == spv::Op::OpLabel) {
            block_of[in[1]] = uint32_t(blocks.size());
            Block nb;
            nb.label = in[1];
            nb.first = nb.end = k + 1;
            blocks.push_back(nb);
        } else if (in.op == spv::Op::OpVariable) {
            // Function-scope variable: local SoA memory.
            if (blocks.empty()) fail("variable outside a block");
            const Type& pt = type(in[1]);
            Pointer p;
            p.space = Space::Local;
            p.type = pt.elem;
            p.base = local_words;
            p.limit = local_words + type(pt.elem).flat;
            local_words += type(pt.elem).flat;
            if (local_words > (1u << 20)) fail("too much variable memory");
            pointers_.push_back(p);
            vals_[in[2]] = Value{kNoReg, in[1], int(pointers_.size() - 1)};
        } else if (!blocks.empty()) {
            Block& b = blocks.back();
            b.end = k + 1;
            if (in.op == spv::Op::OpSelectionMerge) b.merge = in[1];
            if (in.op == spv::Op::OpLoopMerge) {
                b.merge = in[1];
                b.cont = in[2];
            }
            if (in.op == spv::Op::OpBranch) b.succ = {in[1]};
            if (in.op == spv::Op::OpBranchConditional) b.succ = {in[2], in[3]};
            if (in.op == spv::Op::OpSwitch) {
                b.succ.push_back(in[2]);
                for (size_t j = 4; j < in.n; j += 2) b.succ.push_back(in[j]);
            }
        } else if (in.op != spv::Op::OpFunctionParameter) {
            fail("instruction outside a block");
        }
    }
    p_.local_words = local_words;
    if (blocks.empty()) fail("entry point has no body");
    for (auto& b : blocks)
        for (uint32_t s : b.succ)
            if (!block_of.count(s)) fail("branch to unknown block");

    // Structured reverse post-order: merge (and continue) targets are visited first so they end up last.
    std::vector<uint32_t> post;
    std::vector<uint8_t> state(blocks.size(), 0);
    std::vector<std::pair<uint32_t, size_t>> stack{{0, 0}};
    state[0] = 1;
    auto succ_list = [&](uint32_t bi) {
        std::vector<uint32_t> s;
        const Block& b = blocks[bi];
        if (b.merge) s.push_back(block_of.at(b.merge));
        if (b.cont) s.push_back(block_of.at(b.cont));
        for (auto it = b.succ.rbegin(); it != b.succ.rend(); ++it) s.push_back(block_of.at(*it));
        return s;
    };
    std::vector<std::vector<uint32_t>> succs(blocks.size());
    for (uint32_t i = 0; i < blocks.size(); ++i) succs[i] = succ_list(i);
    while (!stack.empty()) {
        auto& [bi, next] = stack.back();
        if (next < succs[bi].size()) {
            uint32_t s = succs[bi][next++];
            if (!state[s]) {
                state[s] = 1;
                stack.push_back({s, 0});
            }
        } else {
            post.push_back(bi);
            stack.pop_back();
        }
    }
    std::vector<uint32_t> order(post.rbegin(), post.rend());
    for (uint32_t i = 0; i < order.size(); ++i) blocks[order[i]].order = int(i);

    // Blocks inside a loop construct: between the header and its merge block in this layout (the merge is visited
    // first, so every block of the loop lands before it). Over-approximating only costs a masked move.
    std::vector<uint8_t> in_loop(blocks.size(), 0);
    for (const Block& h : blocks) {
        if (!h.cont || h.order < 0) continue;
        int lo = h.order, hi = blocks[block_of.at(h.merge)].order;
        if (hi <= lo) hi = int(order.size());
        for (int o = lo; o < hi; ++o) in_loop[order[size_t(o)]] = 1;
    }

    // Masks: entry block starts with the entry mask; the others start empty.
    for (uint32_t i = 0; i < blocks.size(); ++i) {
        blocks[i].mask = alloc();
        emit(SOp::Mov, blocks[i].mask, i == 0 ? p_.reg_entry_mask : zero_);
    }
    // Phi registers are allocated up front so edges can write them before their block is translated.
    for (auto& b : blocks) {
        for (size_t j = b.first; j < b.end; ++j) {
            const Instr& in = ins[j];
            if (in.op != spv::Op::OpPhi) continue;
            uint32_t n = std::max(1u, type(in[1]).flat);
            uint32_t r = alloc(n);
            vals_[in[2]] = Value{r, in[1], -1, true};
            // Lanes that never reach this block would otherwise keep a previous run's value, which a derivative
            // in non-uniform control flow (undefined, but must be deterministic) could read from a neighbour.
            for (uint32_t i = 0; i < n; ++i) emit(SOp::Mov, r + i, zero_);
        }
    }

    // Module-scope initializers run first, for every lane.
    cur_mask_ = konst(~0u);
    for (auto& [ptr, init] : private_inits_) store(pointers_[ptr], pointers_[ptr].type, reg(init), 0);
    for (uint32_t oi = 0; oi < order.size(); ++oi) {
        Block& b = blocks[order[oi]];
        size_t skip_at = p_.code.size();
        b.code = skip_at;
        emit(SOp::JumpIfNone, kNoReg, b.mask);
        cur_mask_ = b.mask;
        store_mask_ = kNoReg;
        in_loop_ = in_loop[order[oi]] != 0;
        size_t j = b.first;
        for (; j + 1 < b.end; ++j) {
            const Instr& in = ins[j];
            if (in.op == spv::Op::OpPhi || in.op == spv::Op::OpSelectionMerge || in.op == spv::Op::OpLoopMerge)
                continue;
            op(in);
        }
        const Instr& term = ins[b.end - 1];
        // Edge masks.
        std::vector<std::pair<uint32_t, uint32_t>> edges;  // (target block, mask register)
        switch (term.op) {
            case spv::Op::OpBranch:
                edges.push_back({block_of.at(term[1]), b.mask});
                break;
            case spv::Op::OpBranchConditional: {
                uint32_t c = reg(term[1]);
                if (term[2] == term[3]) {
                    edges.push_back({block_of.at(term[2]), b.mask});
                } else {
                    edges.push_back({block_of.at(term[2]), emit1(SOp::And, b.mask, c)});
                    edges.push_back({block_of.at(term[3]), emit1(SOp::Select, zero_, b.mask, c)});
                }
                break;
            }
            case spv::Op::OpSwitch: {
                uint32_t sel = reg(term[1]);
                uint32_t rest = b.mask;
                std::map<uint32_t, uint32_t> per_target;
                for (size_t q = 3; q + 1 < term.n; q += 2) {
                    uint32_t eq = emit1(SOp::IEq, sel, konst(term[q]));
                    uint32_t e = emit1(SOp::And, rest, eq);
                    rest = emit1(SOp::Select, zero_, rest, eq);
                    uint32_t t = block_of.at(term[q + 1]);
                    per_target[t] = per_target.count(t) ? emit1(SOp::Or, per_target[t], e) : e;
                }
                uint32_t t = block_of.at(term[2]);
                per_target[t] = per_target.count(t) ? emit1(SOp::Or, per_target[t], rest) : rest;
                for (auto& [tb, m] : per_target) edges.push_back({tb, m});
                break;
            }
            case spv::Op::OpReturn:
            case spv::Op::OpUnreachable:
                break;
            case spv::Op::OpKill:
            case spv::Op::OpTerminateInvocation:
                if (stage_ != Stage::Fragment) fail("OpKill outside a fragment shader");
                iface_.uses_discard = true;
                emit(SOp::Kill, p_.reg_live, b.mask);
                break;
            default:
                fail(std::string("unsupported block terminator ") + names::opcode(uint32_t(term.op)));
        }
        // If this block's mask register is used as an edge mask, copy it before clearing.
        for (auto& e : edges)
            if (e.second == b.mask) e.second = emit1(SOp::Mov, b.mask);
        emit(SOp::Mov, b.mask, zero_);
        int back_target = -1;
        for (auto& [tb, m] : edges) {
            Block& t = blocks[tb];
            // phis of the target: read all incoming values first (a phi may read another phi of the same block)
            std::vector<std::pair<uint32_t, uint32_t>> moves;  // (dst reg, src reg)
            for (size_t q = t.first; q < t.end && ins[q].op == spv::Op::OpPhi; ++q) {
                const Instr& phi = ins[q];
                for (size_t a = 3; a + 1 < phi.n; a += 2) {
                    if (phi[a + 1] != b.label) continue;
                    const Value& dst = vals_[phi[2]];
                    const Value& src = val(phi[a]);
                    uint32_t n = std::max(1u, type(phi[1]).flat);
                    for (uint32_t r = 0; r < n; ++r) moves.push_back({dst.reg + r, src.reg + r});
                }
            }
            std::vector<uint32_t> tmp;
            for (auto& mv : moves) tmp.push_back(emit1(SOp::Mov, mv.second));
            for (size_t q = 0; q < moves.size(); ++q) emit(SOp::MaskedMov, moves[q].first, tmp[q], kNoReg, m);
            emit(SOp::Or, t.mask, t.mask, m);
            if (t.order <= b.order) {
                if (back_target >= 0) fail("block with two back edges");
                back_target = int(tb);
            }
        }
        if (back_target >= 0) {
            // loop back while any lane continues; the blocks after this one must lie outside the loop
            emit(SOp::JumpIfAny, kNoReg, blocks[back_target].mask, kNoReg, kNoReg, uint32_t(blocks[back_target].code));
        }
        p_.code[skip_at].imm = uint32_t(p_.code.size());
        (void)oi;
    }
    emit(SOp::Halt, kNoReg);

    std::sort(iface_.inputs.begin(), iface_.inputs.end(), [](const IoVariable& a, const IoVariable& b) {
        return a.location * 4 + a.component < b.location * 4 + b.component;
    });
    std::sort(iface_.outputs.begin(), iface_.outputs.end(), [](const IoVariable& a, const IoVariable& b) {
        return a.location * 4 + a.component < b.location * 4 + b.component;
    });
    for (auto& d : iface_.descriptors)
        if (d.kind == DescriptorKind::StorageBuffer) d.written = buffer_written_;
    std::sort(iface_.descriptors.begin(), iface_.descriptors.end(), [](const DescriptorUse& a, const DescriptorUse& b) {
        return a.set != b.set ? a.set < b.set : a.binding < b.binding;
    });
}

std::string translate(const std::vector<uint32_t>& spirv, Stage stage, std::string_view entry, ProgramImpl& out,
                      ProgramInterface& iface) {
    Translator t(stage, out, iface);
    try {
        t.run(spirv, entry);
    } catch (const TranslateError& e) {
        return e.message;
    } catch (const std::exception& e) {
        return std::string("translation failed: ") + e.what();
    }
    return {};
}

}  // namespace tilevk::shader
