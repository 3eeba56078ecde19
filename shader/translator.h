// SPIR-V -> SIMD program translator state, shared by translate.cpp (module, types, interface, control flow)
// and translate_ops.cpp (one SPIR-V instruction at a time).
#pragma once

#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#define SPV_ENABLE_UTILITY_CODE
#include <spirv/unified1/spirv.hpp11>

#include "shader/ir.h"
#include "shader/spirv_names.h"

namespace tilevk::shader {

const char* glsl_std450_name(uint32_t opcode);  // "MatrixInverse", ... (translate_glsl.cpp)

struct TranslateError {
    std::string message;
};

struct Type {
    enum Kind {
        Void,
        Bool,
        Int,
        Float,
        Vector,
        Matrix,
        Array,
        RuntimeArray,
        Struct,
        Pointer,
        Function,
        Image,
        Sampler,
        SampledImage
    } kind = Void;
    bool is_signed = false;
    uint32_t elem = 0;   // component / column / element / pointee / image type
    uint32_t count = 0;  // vector size, columns, array length
    std::vector<uint32_t> members;
    spv::StorageClass storage = spv::StorageClass::Function;
    uint32_t flat = 0;  // number of 32-bit scalars when flattened (registers a value of this type occupies)
    uint32_t dim = 0, arrayed = 0, ms = 0, sampled = 0;  // images
    uint32_t bits = 32;  // Int / Float: 8 or 16 for the narrow types (one zero-extended register; translate_narrow.cpp)
    bool wide = false;   // a 64-bit integer (two registers: low word, high word; translate_pointer.cpp)
};

struct Decorations {
    int location = -1, component = 0, builtin = -1;
    int index = 0;  // fragment outputs: 1 = the second source of dual-source blending
    bool flat = false, noperspective = false, centroid = false, sample = false;
    int set = -1, binding = -1, offset = -1, array_stride = 0, matrix_stride = 0;
    bool row_major = false, block = false, buffer_block = false, non_writable = false;
};

// Local: SoA words, one per lane; Shared: compute's Workgroup memory, flat words every lane sees (both addressed
// by word, with the same flat layout); Buffer: bytes through a descriptor; Handle: image/sampler descriptors.
// Texel: an OpImageTexelPointer (image atomics): base = the image handle register, dyn = the first coordinate
// register, offset = kSampleArray or 0.
// Phys: a PhysicalStorageBuffer pointer (translate_pointer.cpp): base = the first of the two registers holding its
// address (low word, high word), offset = a constant byte offset; buffer layout as Buffer.
enum class Space : uint8_t { Local, Shared, Buffer, Handle, Texel, Phys };

struct Pointer {
    Space space = Space::Local;
    uint32_t type = 0;       // pointee type
    uint32_t base = 0;       // Local: first word; Buffer/Handle: first descriptor slot
    uint32_t limit = 0;      // Local: one past the variable's last word; Buffer/Handle: array size
    uint32_t dyn = kNoReg;   // dynamic offset register (words / bytes), kNoReg = none
    uint32_t offset = 0;     // constant offset (words / bytes)
    uint32_t elem = kNoReg;  // Buffer/Handle: dynamic descriptor array element register
    uint32_t elem_const = 0;
    bool in_array = false;  // Buffer/Handle: still pointing at the descriptor array itself
    // buffer layout of what is pointed at
    // vec_stride: bytes between a vector's components, 0 = the component's own size (4, or 8 for 64-bit types);
    // a row-major matrix's column vectors step by the matrix stride
    uint32_t vec_stride = 0, matrix_stride = 16;
    bool row_major = false;
    bool writable = false;
};

struct Value {
    uint32_t reg = kNoReg;  // first register (flat layout)
    uint32_t type = 0;
    int ptr = -1;  // index into Translator::pointers
    bool is_phi = false;
};

struct Block {
    uint32_t label = 0;
    size_t first = 0, end = 0;  // instruction index range (after OpLabel, up to and including terminator)
    uint32_t merge = 0, cont = 0;
    std::vector<uint32_t> succ;
    uint32_t mask = kNoReg;
    int order = -1;
    size_t code = 0;  // code position of the block's first instruction
};

struct Instr {
    spv::Op op;
    const uint32_t* w;  // w[0] = word count | opcode
    uint32_t n;
    uint32_t operator[](size_t i) const { return w[i]; }
};

// The literal string starting at word `at` of an instruction (translate_module.cpp).
std::string literal_string(const Instr& in, size_t at);
// "vertex", "fragment", "compute", for messages.
inline const char* stage_name(Stage s) {
    return s == Stage::Vertex ? "vertex" : s == Stage::Fragment ? "fragment" : "compute";
}
// "OpFAdd", ... for messages.
inline std::string opname(spv::Op op) {
    return names::opcode(uint32_t(op));
}

class Translator {
  public:
    Translator(Stage stage, ProgramImpl& out, ProgramInterface& iface) : stage_(stage), p_(out), iface_(iface) {}
    void run(const std::vector<uint32_t>& words, std::string_view entry);

    // phases (translate.cpp, translate_module.cpp, translate_interface.cpp, translate_control.cpp)
    void find_entry_point(std::string_view entry);
    void declare(const Instr& in);  // one module-level instruction
    void declare_execution_mode(const Instr& in);
    void decorate(const Instr& in);
    void declare_type(const Instr& in);
    void declare_composite_type(const Instr& in, Type& t);
    void declare_image_type(const Instr& in, Type& t);
    void declare_constant(const Instr& in);
    void resolve_local_size();  // compute: LocalSizeId operands, once the constants are declared
    void declare_variable(const Instr& in);
    void walk_interface(bool out, uint32_t ty, uint32_t word, int loc, int comp, const Decorations& dd, int builtin);
    void declare_resource(spv::StorageClass sc, const Decorations& d, Pointer& p);
    void collect_blocks(size_t fn_begin);
    void order_blocks();
    void init_masks_and_phis();
    void emit_blocks();
    std::vector<std::pair<uint32_t, uint32_t>> edges_of(const Block& b, const Instr& term);
    void emit_terminator(Block& b, const Instr& term);
    void finish_interface();

    // one instruction (translate_ops.cpp), by family; each returns false for an opcode outside it
    void op(const Instr& in);
    bool op_arith(const Instr& in);
    bool op_logic(const Instr& in);
    bool op_composite(const Instr& in);
    bool op_fragment(const Instr& in);
    bool op_memory(const Instr& in);    // translate_memory.cpp
    bool op_image(const Instr& in);     // translate_image.cpp
    bool op_atomic(const Instr& in);    // translate_atomic.cpp: OpAtomic*, OpControlBarrier
    bool op_subgroup(const Instr& in);  // translate_subgroup.cpp: OpGroupNonUniform* (compute)
    bool op_dot(const Instr& in);       // translate_dot.cpp: OpSDot, OpUDot, OpSUDot (+AccSat)
    // translate_pointer.cpp: PhysicalStorageBuffer pointers and the 64-bit integer arithmetic on their addresses
    bool op_pointer(const Instr& in);
    // translate_wide.cpp: 64-bit integers and doubles (two registers per scalar, Op::Wide)
    bool op_wide(const Instr& in);
    bool op_wide_convert(const Instr& in);
    bool op_wide_composite(const Instr& in);
    bool op_wide_matrix(const Instr& in);
    bool glsl_wide(const Instr& in);
    bool glsl_wide_composite(const Instr& in, uint32_t e);
    bool is_wide_type(uint32_t t) const;       // a 64-bit scalar, or a vector or matrix of them
    bool is_wide_value(uint32_t id) const;     // a value of such a type
    uint32_t words_of(uint32_t t) const;       // registers per component: 2 for 64-bit types, else 1
    uint32_t components_of(uint32_t t) const;  // scalars in a scalar/vector/matrix type
    uint32_t konst64(uint64_t v);              // two constant registers
    // one Op::Wide (d = kNoReg: new registers); returns d
    uint32_t wide(WideOp o, uint32_t d, uint32_t a, uint32_t b = kNoReg, uint32_t c = kNoReg);
    void wide_each(const Instr& in, WideOp o, std::initializer_list<uint32_t> ids, uint32_t d = kNoReg);
    uint32_t dot64(uint32_t a, uint32_t b, uint32_t n);
    std::unordered_map<uint32_t, uint32_t> f2s_of_;  // OpConvertFToS result id -> its double operand id
    // translate_narrow.cpp: 8- and 16-bit integers, 16-bit float storage (one zero-extended register per scalar)
    bool op_narrow(const Instr& in);
    bool op_narrow_convert(const Instr& in);
    bool bitcast_pieces(const Instr& in);
    bool glsl_narrow(const Instr& in);
    uint32_t narrow_bits(uint32_t t) const;  // 8 or 16 for a narrow scalar or vector type, else 0
    bool is_narrow_value(uint32_t id) const;
    uint32_t bits_of(uint32_t t) const;        // component width: 8, 16, 32 or 64
    uint32_t sext(uint32_t r, uint32_t bits);  // r sign-extended from `bits` (a new register; r itself when 32)
    uint32_t wrap(uint32_t r, uint32_t bits);  // the low `bits` of r
    uint32_t narrow_operand(uint32_t id, uint32_t i, bool is_signed);
    bool is_phys_pointer(uint32_t type_id) const;
    Pointer phys_pointer(uint32_t id);                  // the pointer a PhysicalStorageBuffer pointer value holds
    uint32_t address_add(uint32_t addr, uint32_t off);  // two registers: addr + sign-extended 32-bit off
    void phys_access_chain(const Instr& in, uint32_t base_id, uint32_t elem, size_t first_index);
    void load_phys(const Pointer& p, uint32_t type, uint32_t dst);
    void store_phys(const Pointer& p, uint32_t type, uint32_t src);
    uint32_t packed_byte(uint32_t x, uint32_t k, bool is_signed);
    bool subgroup_collective(const Instr& in);
    void subgroup_ballot_helper(const Instr& in);
    uint32_t side_effect_mask();  // lanes whose buffer writes take effect (fragment: live ones only)
    bool image_sample(const Instr& in);
    void storage_image_access(const Instr& in);
    void image_texel_pointer(const Instr& in);                       // OpImageTexelPointer (translate_image.cpp)
    uint32_t storage_coord(const Type& image_type, uint32_t coord);  // its (x, y[, layer]) registers  // OpImageRead /
                                                                     // OpImageWrite on a storage image
    void glsl_op(const Instr& in);               // translate_glsl.cpp: GLSL.std.450
    void interpolate_at(const Instr& in, uint32_t e);  // its InterpolateAt* (translate_interface.cpp)
    // helpers for instructions with a result (type in[1], id in[2])
    uint32_t def(const Instr& in, uint32_t n = 0);  // n registers (default: the result type's) for the result
    void alias(const Instr& in, uint32_t r);        // the result is register run r
    uint32_t flat_of(uint32_t id);                  // registers of a value
    bool unary(const Instr& in, Op o);              // o per component
    bool binary(const Instr& in, Op o);             // o per component; a scalar operand is broadcast
    bool swapped(const Instr& in, Op o);            // o with the operands swapped (a > b == b < a)
    uint32_t dot(uint32_t a, uint32_t b, uint32_t n);

    [[noreturn]] static void fail(const std::string& m) { throw TranslateError{m}; }

    // registers and emission
    uint32_t alloc(uint32_t n = 1) {
        uint32_t r = p_.num_regs;
        p_.num_regs += n;
        return r;
    }
    uint32_t konst(uint32_t v);
    uint32_t konstf(float f);
    Inst& emit(Op op, uint32_t d, uint32_t a = kNoReg, uint32_t b = kNoReg, uint32_t c = kNoReg, uint32_t imm = 0,
               uint32_t extra = 0) {
        Inst in{op, 0, d, a, b, c, imm, extra};
        p_.code.push_back(in);
        return p_.code.back();
    }
    uint32_t emit1(Op op, uint32_t a = kNoReg, uint32_t b = kNoReg, uint32_t c = kNoReg) {
        uint32_t d = alloc();
        emit(op, d, a, b, c);
        return d;
    }

    const Type& type(uint32_t id) const;
    Value& val(uint32_t id);
    uint32_t reg(uint32_t id) { return val(id).reg; }
    uint32_t component_type(uint32_t t) const;  // scalar type of a scalar/vector/matrix
    uint32_t scalar_bytes(uint32_t t) const {   // buffer size of a scalar type
        return type(t).wide ? 8 : type(t).bits < 32 ? type(t).bits / 8 : 4;
    }
    uint32_t flat_index(uint32_t t, const uint32_t* idx, size_t n, uint32_t* out_type) const;

    // memory
    void load(const Pointer& p, uint32_t type, uint32_t dst, uint32_t const_extra);
    void store(const Pointer& p, uint32_t type, uint32_t src, uint32_t const_extra);
    // The one walk of a buffer value's layout (Offset, ArrayStride, MatrixStride, RowMajor decorations) for load and
    // store: scalar(register, byte offset, scalar type) for every scalar of `type`, in flat register order.
    template <typename Scalar>
    void walk_buffer_layout(const Pointer& p, uint32_t type, uint32_t reg, uint32_t off, const Scalar& scalar);
    Pointer access_chain(const Pointer& base, const uint32_t* idx, size_t n);
    // The buffer layout rules both walk_buffer_layout and access_chain follow (translate_memory.cpp): a struct
    // member's Offset (failing without one), after which `p` has the member's MatrixStride and RowMajor; an array's
    // ArrayStride (failing without one); the bytes between a vector's components; a matrix's column and row steps.
    uint32_t enter_member(Pointer& p, uint32_t struct_type, uint32_t m);
    void touch_distance_words(const Pointer& p, uint32_t off, uint32_t words);  // a Local access
    uint32_t buffer_array_stride(uint32_t array_type);
    uint32_t vector_stride(const Pointer& p, uint32_t vector_type) const;
    struct MatrixSteps {
        uint32_t column, row;
    };
    MatrixSteps matrix_steps(const Pointer& p, uint32_t matrix_type) const;

    Stage stage_;
    ProgramImpl& p_;
    ProgramInterface& iface_;
    uint32_t bound_ = 0;
    std::vector<Instr> ins_;
    uint32_t entry_fn_ = 0;
    std::vector<uint32_t> entry_iface_;  // the entry point's interface variables
    uint32_t local_words_ = 0;           // SoA local memory words allocated so far
    uint32_t shared_words_ = 0;          // Workgroup memory words allocated so far
    // The local words [first, end) of the ClipDistance (0) and CullDistance (1) outputs, and whether a store reaches
    // them: an array no store writes counts as absent (finish_interface), as lavapipe ignores the unwritten
    // gl_CullDistance[1] glslang declares next to gl_ClipDistance (cts clipping.clip_distance.nine_vertex_batch).
    uint32_t distance_words_[2][2] = {};
    bool distance_written_[2] = {};
    uint32_t next_slot_ = 1;             // next descriptor slot (slot 0: push constants)
    std::vector<Block> blocks_;
    std::unordered_map<uint32_t, uint32_t> block_of_;  // label -> index into blocks_
    std::vector<uint32_t> order_;                      // blocks_ indices in layout order
    std::vector<uint8_t> block_in_loop_;               // per block: lies inside a loop construct
    std::vector<Type> types_;
    std::vector<uint8_t> is_type_;
    std::vector<Decorations> deco_;
    std::map<std::pair<uint32_t, uint32_t>, Decorations> member_deco_;
    std::vector<Value> vals_;
    std::vector<Pointer> pointers_;
    std::unordered_map<uint32_t, uint32_t> const_regs_;  // value -> register
    std::unordered_map<uint32_t, uint32_t> reg_value_;   // constant register -> value
    bool const_of(uint32_t id, uint32_t& v) const {
        if (id >= bound_ || vals_[id].reg == kNoReg) return false;
        auto it = reg_value_.find(vals_[id].reg);
        if (it == reg_value_.end()) return false;
        v = it->second;
        return true;
    }
    // `id` is a constant whose `flat` registers all hold 0 (OpConstantNull, or a composite of zeros).
    bool is_zero_constant(uint32_t id, uint32_t flat) const {
        if (id >= bound_ || vals_[id].reg == kNoReg) return false;
        for (uint32_t j = 0; j < flat; ++j) {
            auto it = reg_value_.find(vals_[id].reg + j);
            if (it == reg_value_.end() || it->second != 0) return false;
        }
        return true;
    }
    void set_const(uint32_t reg, uint32_t v) {
        p_.const_regs.push_back(reg);
        p_.const_regs.push_back(v);
        reg_value_[reg] = v;
    }
    uint32_t glsl_ext_ = 0;
    uint32_t local_size_ids_[3] = {0, 0, 0};  // ExecutionModeId LocalSizeId operands (0: none)
    bool workgroup_size_builtin_ = false;     // a constant decorated BuiltIn WorkgroupSize set the local size
    uint32_t cur_mask_ = kNoReg;              // mask register of the block being translated
    uint32_t zero_ = kNoReg;
    // Local word of a hidden copy of gl_FragCoord.xy, made when the module declares a SubpassData image:
    // subpassLoad reads the input attachment at the fragment's own pixel (kNoReg: none).
    uint32_t subpass_coord_word_ = kNoReg;
    std::vector<uint32_t> store_masks_;  // per block: mask for side effects
    uint32_t store_mask_ = kNoReg;
    bool buffer_written_ = false;
    bool image_written_ = false;  // an OpImageWrite (storage images)
    // The block being translated lies inside a loop. Instructions there run for all lanes on every iteration, so
    // a lane that already left the loop has its registers recomputed. That is harmless for pure functions of its
    // own (masked) phis and memory, but not for results that depend on other lanes or shared memory: buffer loads,
    // derivatives and implicit-LOD sampling. Those are written under the block mask (keep_active) in loops.
    bool in_loop_ = false;
    // Emit `gen(tmp)` computing n registers, then move them into d..d+n-1 for the block's lanes only (in loops).
    template <typename Gen>
    void keep_active(uint32_t d, uint32_t n, Gen gen) {
        if (!in_loop_) return gen(d);
        uint32_t tmp = alloc(n);
        gen(tmp);
        for (uint32_t i = 0; i < n; ++i) emit(Op::MaskedMov, d + i, tmp + i, kNoReg, cur_mask_);
    }
    std::vector<std::pair<uint32_t, uint32_t>> private_inits_;  // (pointer index, initializer id)
};

}  // namespace tilevk::shader
