// Images: sampling (implicit/explicit LOD, bias, gradients, projection, depth comparison, constant offsets),
// texel fetches (also of uniform texel buffers and of multisampled images), input attachments, size, level and
// sample-count queries.
#include "shader/translator.h"

namespace tilevk::shader {

using SOp = tilevk::shader::Op;

// Sampling and texel fetches: the image operands (bias, LOD, gradients, constant offset) into one Sample/Fetch.
bool Translator::image_sample(const Instr& in) {
    const Type& it =
        type(type(val(in[3]).type).kind == Type::SampledImage ? type(val(in[3]).type).elem : val(in[3]).type);
    // Integer sampled types read the texels' integers (the format decides: texture.cpp); no depth comparison.
    const bool integer = type(it.elem).kind != Type::Float;
    uint32_t flags = 0;
    if (it.arrayed) flags |= kSampleArray;
    if (spv::Dim(it.dim) == spv::Dim::Dim1D) flags |= kSample1D;
    const bool three_d = spv::Dim(it.dim) == spv::Dim::Dim3D;
    if (three_d) flags |= kSample3D;  // texture_3d.cpp
    const spv::Op o = in.op;
    const bool cube = spv::Dim(it.dim) == spv::Dim::Cube;
    if (cube) {
        if (o == spv::Op::OpImageFetch) fail("OpImageFetch on a cube image");
        flags |= kSampleCube;
    }
    if (spv::Dim(it.dim) == spv::Dim::Buffer) {
        if (o != spv::Op::OpImageFetch) fail("texel buffers are read with texelFetch only");
        flags |= kSample1D;  // one row of `range / texel size` texels, level 0
    }
    const bool gather = o == spv::Op::OpImageGather || o == spv::Op::OpImageDrefGather;
    bool dref = o == spv::Op::OpImageSampleDrefImplicitLod || o == spv::Op::OpImageSampleDrefExplicitLod ||
                o == spv::Op::OpImageSampleProjDrefImplicitLod || o == spv::Op::OpImageSampleProjDrefExplicitLod ||
                o == spv::Op::OpImageDrefGather;
    bool proj = o == spv::Op::OpImageSampleProjImplicitLod || o == spv::Op::OpImageSampleProjExplicitLod ||
                o == spv::Op::OpImageSampleProjDrefImplicitLod || o == spv::Op::OpImageSampleProjDrefExplicitLod;
    bool implicit = o == spv::Op::OpImageSampleImplicitLod || o == spv::Op::OpImageSampleProjImplicitLod ||
                    o == spv::Op::OpImageSampleDrefImplicitLod || o == spv::Op::OpImageSampleProjDrefImplicitLod;
    if (integer && dref) fail("depth comparison on an integer image");
    if (three_d && dref) fail("depth comparison on a 3D image");
    if (proj) flags |= kSampleProj;
    uint32_t lod = kNoReg, grad = 0;
    // The Dref variants carry the reference, OpImageGather its component, before the image operands.
    size_t first_op = dref || gather ? 6 : 5;
    if (gather) {
        if (spv::Dim(it.dim) != spv::Dim::Dim2D) fail(opname(o) + " on an image that is not 2D (no cube images)");
        uint32_t comp = 0;
        if (o == spv::Op::OpImageGather && (!const_of(in[5], comp) || comp > 3))
            fail("OpImageGather: the component is not a constant 0..3");
        flags |= kSampleGather | comp << kSampleGatherCompShift;
    }
    uint32_t operands = in.n > first_op ? in[first_op] : 0;
    size_t at = first_op + 1;
    if (operands & uint32_t(spv::ImageOperandsMask::Bias)) {
        flags |= kSampleBias;
        lod = reg(in[at++]);
    }
    if (operands & uint32_t(spv::ImageOperandsMask::Lod)) {
        flags |= kSampleExplicitLod;
        lod = reg(in[at++]);
    }
    if (operands & uint32_t(spv::ImageOperandsMask::Grad)) {
        flags |= kSampleGrad;
        uint32_t gx = reg(in[at++]), gy = reg(in[at++]);
        // dx then dy, two components each (x, y); three for 3D and for a cube's direction (texture_3d.cpp,
        // texture_cube.cpp); 1D's second ones are 0
        const uint32_t nc = (flags & kSample1D) ? 1 : 2, per = three_d || cube ? 3 : 2;
        grad = alloc(2 * per);
        for (uint32_t i = 0; i < per; ++i) {
            emit(SOp::Mov, grad + i, i < nc || per == 3 ? gx + i : zero_);
            emit(SOp::Mov, grad + per + i, i < nc || per == 3 ? gy + i : zero_);
        }
    }
    if (operands & uint32_t(spv::ImageOperandsMask::ConstOffset)) {
        // On 3D, lavapipe's float filter adds the offset to r in a way not matched yet (1-ulp weight differences
        // with REPEAT, cts texture.3d): refused rather than approximated.
        if (three_d) fail("a constant texel offset on a 3D image (textureOffset on sampler3D) is not supported");
        const Value& ov = val(in[at++]);
        uint32_t nc = std::max(1u, type(ov.type).flat);
        int32_t off[2] = {0, 0};
        for (uint32_t i = 0; i < nc && i < 2; ++i) {
            auto found = reg_value_.find(ov.reg + i);
            if (found == reg_value_.end()) fail("texel offset is not a constant");
            off[i] = int32_t(found->second);
            if (off[i] < -128 || off[i] > 127) fail("texel offset out of range");
        }
        flags |= kSampleOffset | (uint32_t(uint8_t(int8_t(off[0]))) << 16) | (uint32_t(uint8_t(int8_t(off[1]))) << 24);
    }
    if (cube && (flags & kSampleOffset)) fail(opname(o) + " with a texel offset on a cube image");
    // texelFetch(sampler2DMS[Array], p, sample): level 0 of the view, the sample's plane (texture.cpp exec_fetch)
    if (operands & uint32_t(spv::ImageOperandsMask::Sample)) {
        if (o != spv::Op::OpImageFetch || !it.ms) fail("a Sample image operand outside a multisampled texel fetch");
        flags |= kSampleMs;
        lod = reg(in[at++]);
    } else if (it.ms) {
        fail(opname(o) + " on a multisampled image without a sample index");
    }
    // SignExtend / ZeroExtend (SPIR-V 1.4; glslang marks every integer sample and fetch with them) take no operand
    // words and change nothing here: texels are widened to 32 bits by their format's own signedness.
    if (gather && (operands & uint32_t(spv::ImageOperandsMask::Offset | spv::ImageOperandsMask::ConstOffsets)))
        fail(opname(o) + " with a non-constant offset or four offsets (shaderImageGatherExtended is not supported)");
    uint32_t other =
        operands & ~uint32_t(spv::ImageOperandsMask::Bias | spv::ImageOperandsMask::Lod | spv::ImageOperandsMask::Grad |
                             spv::ImageOperandsMask::ConstOffset | spv::ImageOperandsMask::Sample |
                             spv::ImageOperandsMask::SignExtend | spv::ImageOperandsMask::ZeroExtend);
    if (other) fail("unsupported image operands (dynamic offsets, min lod) in " + opname(o));
    if (gather && (flags & (kSampleBias | kSampleExplicitLod | kSampleGrad)))
        fail(opname(o) + " with a bias, LOD or gradients");
    if (implicit) {
        if (stage_ != Stage::Fragment) fail("implicit-LOD sampling outside a fragment shader");
        flags |= kSampleImplicitLod;
        iface_.uses_derivatives = true;
    }
    uint32_t ncoord = flat_of(in[4]);
    uint32_t coords = reg(in[4]);
    uint32_t d;
    if (dref) {
        // coordinates followed by the reference in one register run; the result is a scalar
        flags |= kSampleDref;
        coords = alloc(ncoord + 1);
        for (uint32_t i = 0; i < ncoord; ++i) emit(SOp::Mov, coords + i, reg(in[4]) + i);
        emit(SOp::Mov, coords + ncoord, reg(in[5]));
        ++ncoord;
        d = alloc(4);  // OpImageDrefGather's four comparisons, the other forms' scalar in the first
        vals_[in[2]] = Value{d, in[1]};
    } else {
        if (type(in[1]).flat != 4) fail("image result must be a 4-component vector");
        d = def(in, 4);
    }
    auto sample = [&](uint32_t t) {
        Inst& si = emit(o == spv::Op::OpImageFetch ? SOp::Fetch : SOp::Sample, t, reg(in[3]), coords,
                        lod == kNoReg ? zero_ : lod, flags, ncoord);
        si.n = grad;
    };
    if (implicit)  // the LOD comes from neighbour lanes' coordinates
        keep_active(d, 4, sample);
    else
        sample(d);
    return true;
}

// The coordinate registers of a storage image access: the coordinate's own (x, y[, layer]), or for a storage texel
// buffer (x, 0) (the view is one row).
uint32_t Translator::storage_coord(const Type& it, uint32_t coord) {
    if (spv::Dim(it.dim) == spv::Dim::Buffer) {
        const uint32_t xy = alloc(2);
        emit(SOp::Mov, xy, reg(coord));
        emit(SOp::Mov, xy + 1, zero_);
        return xy;
    }
    if (flat_of(coord) < (it.arrayed ? 3u : 2u)) fail("storage image coordinate with too few components");
    return reg(coord);
}

// imageLoad / imageStore on a storage image (2D or 2D array, declare_image_type) or a storage texel buffer: integer
// coordinates, the view's
// format decides the conversion (texture.cpp), as lavapipe's lp_build_img_op_soa does with the bound view's format.
void Translator::storage_image_access(const Instr& in) {
    const bool write = in.op == spv::Op::OpImageWrite;
    const uint32_t image = write ? in[1] : in[3], coord = write ? in[2] : in[4];
    const Type& it = type(val(image).type);
    if (it.kind != Type::Image || it.sampled != 2 || spv::Dim(it.dim) == spv::Dim::SubpassData)
        fail(opname(in.op) + " on an image that is not a storage image");
    const size_t operands_at = write ? 4 : 5;
    // The Vulkan memory model's texel operands (and their scope ids, which follow) change nothing here: a
    // workgroup runs on one thread and every access goes straight to the image's memory.
    const uint32_t allowed =
        uint32_t(spv::ImageOperandsMask::SignExtend | spv::ImageOperandsMask::ZeroExtend |
                 spv::ImageOperandsMask::MakeTexelAvailable | spv::ImageOperandsMask::MakeTexelVisible |
                 spv::ImageOperandsMask::NonPrivateTexel | spv::ImageOperandsMask::VolatileTexel);
    if (in.n > operands_at && (in[operands_at] & ~allowed) != 0)
        fail("unsupported image operands (sample, lod, offsets) in " + opname(in.op));
    const uint32_t flags = it.arrayed ? uint32_t(kSampleArray) : 0u;
    const uint32_t xy = storage_coord(it, coord);
    if (!write) {
        if (type(in[1]).flat != 4) fail("image result must be a 4-component vector");
        const uint32_t d = def(in, 4);
        // another lane (or workgroup) may have stored to the texel: keep what each lane loaded while active
        keep_active(d, 4, [&](uint32_t t) { emit(SOp::ImageLoad, t, reg(image), xy, kNoReg, flags); });
        return;
    }
    const uint32_t n = flat_of(in[3]);
    if (n > 4) fail("storage image texel with more than 4 components");
    uint32_t texel = reg(in[3]);
    if (n < 4) {  // missing components are 0 (never read by the formats that lack them)
        texel = alloc(4);
        for (uint32_t i = 0; i < 4; ++i) emit(SOp::Mov, texel + i, i < n ? reg(in[3]) + i : zero_);
    }
    emit(SOp::ImageStore, side_effect_mask(), reg(image), xy, texel, flags);
    image_written_ = true;
}

// OpImageTexelPointer (the address of an image atomic): a Texel pointer to the texel of a 2D or 2D-array storage
// image or a storage texel buffer, used only by the OpAtomic* that follow (translate_atomic.cpp).
void Translator::image_texel_pointer(const Instr& in) {
    const Value& iv = val(in[3]);
    if (iv.ptr < 0) fail("OpImageTexelPointer on a non-pointer");
    const Pointer ip = pointers_[size_t(iv.ptr)];
    const Type& it = type(ip.type);
    if (ip.space != Space::Handle || it.kind != Type::Image || it.sampled != 2 || it.ms != 0 ||
        (spv::Dim(it.dim) != spv::Dim::Dim2D && spv::Dim(it.dim) != spv::Dim::Buffer))
        fail(
            "unsupported OpImageTexelPointer (image atomics: 2D and 2D-array single-sample storage images and "
            "storage texel buffers only)");
    uint32_t sample = 0;
    if (!const_of(in[5], sample) || sample != 0) fail("OpImageTexelPointer with a sample index");
    Pointer p;
    p.space = Space::Texel;
    p.type = type(in[1]).elem;
    p.base = alloc();
    load(ip, ip.type, p.base, 0);
    p.dyn = storage_coord(it, in[4]);
    p.offset = it.arrayed ? uint32_t(kSampleArray) : 0u;
    p.writable = true;
    pointers_.push_back(p);
    vals_[in[2]] = Value{kNoReg, in[1], int(pointers_.size() - 1)};
}

// Sampled images, texel fetches, input attachments, size queries.
bool Translator::op_image(const Instr& in) {
    switch (in.op) {
        // images
        case spv::Op::OpSampledImage:
            emit(SOp::Or, def(in), reg(in[3]), reg(in[4]));
            return true;
        case spv::Op::OpImage:
            emit(SOp::And, def(in), reg(in[3]), konst(0xFFFF));
            return true;
        case spv::Op::OpImageSampleImplicitLod:
        case spv::Op::OpImageSampleExplicitLod:
        case spv::Op::OpImageSampleProjImplicitLod:
        case spv::Op::OpImageSampleProjExplicitLod:
        case spv::Op::OpImageFetch:
        case spv::Op::OpImageSampleDrefImplicitLod:
        case spv::Op::OpImageSampleDrefExplicitLod:
        case spv::Op::OpImageSampleProjDrefImplicitLod:
        case spv::Op::OpImageSampleProjDrefExplicitLod:
        case spv::Op::OpImageGather:
        case spv::Op::OpImageDrefGather:
            return image_sample(in);
        case spv::Op::OpImageWrite:
            storage_image_access(in);
            return true;
        case spv::Op::OpImageTexelPointer:
            image_texel_pointer(in);
            return true;
        case spv::Op::OpImageRead: {
            const Type& read_type = type(val(in[3]).type);
            if (read_type.kind == Type::Image && spv::Dim(read_type.dim) != spv::Dim::SubpassData) {
                storage_image_access(in);  // an input attachment is sampled == 2 too
                return true;
            }
            // subpassLoad(input, offset): texelFetch(input, ivec2(gl_FragCoord.xy) + offset, 0) on the bound
            // view (lavapipe lowers it the same way, nir_lower_input_attachments with frag coords).
            const Type& it = type(val(in[3]).type);
            if (it.kind != Type::Image || spv::Dim(it.dim) != spv::Dim::SubpassData)
                fail("unsupported storage image read (imageLoad)");
            const uint32_t extend =
                uint32_t(spv::ImageOperandsMask::SignExtend | spv::ImageOperandsMask::ZeroExtend);  // as for samples
            if (in.n > 5 && (in[5] & ~extend) != 0) fail("unsupported image operands on subpassLoad");
            if (type(in[1]).flat != 4) fail("image result must be a 4-component vector");
            if (subpass_coord_word_ == kNoReg) fail("input attachment without its pixel coordinate");
            uint32_t coords = alloc(2);
            for (uint32_t i = 0; i < 2; ++i) {
                uint32_t xy = alloc(1);
                emit(SOp::LoadLocalFixed, xy, kNoReg, kNoReg, kNoReg, subpass_coord_word_ + i);
                emit(SOp::IAdd, coords + i, emit1(SOp::F2S, xy), reg(in[4]) + i);
            }
            emit(SOp::Fetch, def(in, 4), reg(in[3]), coords, zero_, 0u, 2u);
            return true;
        }
        case spv::Op::OpImageQuerySizeLod:
        case spv::Op::OpImageQuerySize: {
            const Type& it = type(val(in[3]).type);
            uint32_t flags =
                (it.arrayed ? uint32_t(kSampleArray) : 0u) |
                (spv::Dim(it.dim) == spv::Dim::Cube ? uint32_t(kSampleCube) : 0u) |
                (spv::Dim(it.dim) == spv::Dim::Dim1D || spv::Dim(it.dim) == spv::Dim::Buffer ? uint32_t(kSample1D)
                                                                                             : 0u) |
                (spv::Dim(it.dim) == spv::Dim::Dim3D ? uint32_t(kSample3D) : 0u);
            uint32_t lod = in.op == spv::Op::OpImageQuerySizeLod ? reg(in[4]) : zero_;
            emit(SOp::QuerySize, def(in), reg(in[3]), lod, kNoReg, flags, std::max(1u, type(in[1]).flat));
            return true;
        }
        case spv::Op::OpImageQueryLevels:
            emit(SOp::QueryLevels, def(in), reg(in[3]));
            return true;
        case spv::Op::OpImageQuerySamples:  // textureSamples: the view's sample count (lavapipe: num_samples)
            emit(SOp::QueryLevels, def(in), reg(in[3]), kNoReg, kNoReg, kSampleMs);
            return true;
        default:
            return false;
    }
}

}  // namespace tilevk::shader
