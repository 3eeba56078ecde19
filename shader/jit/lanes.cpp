// Lane-wise ops, one 8-lane half at a time, and the register allocation inside a segment. Each lowering computes
// exactly what exec.cpp's case computes: the same IEEE operations in the same order (no FMA contraction, no
// reassociation), the same NaN operand order, the same bitwise selects, under the same MXCSR (FTZ + DAZ).
#include <bit>
#include <cstddef>
#include <optional>
#include <utility>

#include "shader/gallivm_math.h"
#include "shader/jit/codegen.h"
#include "shader/jit/helpers.h"

namespace tilevk::shader::jit {

using namespace asmjit;

namespace {

// vcmpps predicates
enum : uint32_t {
    kEqOQ = 0x00,
    kLtOS = 0x01,
    kLeOS = 0x02,
    kUnordQ = 0x03,
    kNeqUQ = 0x04,
    kNltUS = 0x05,
    kNleUS = 0x06,
    kEqUQ = 0x08,
    kNgeUS = 0x09,
    kNgtUS = 0x0A,
    kNeqOQ = 0x0C,
    kGeOS = 0x0D,
    kGtOS = 0x0E,
    kLtOQ = 0x11,
    kGeOQ = 0x1D,
    kGtOQ = 0x1E,
};
// vroundps modes, as GCC emits them for floorf / ceilf / truncf / nearbyintf
enum : uint32_t { kFloor = 0x9, kCeil = 0xA, kTrunc = 0xB, kNearby = 0xC };

constexpr uint32_t fbits(float f) {
    return std::bit_cast<uint32_t>(f);
}

}  // namespace

// --- constant pool ----------------------------------------------------------------------------------------------

x86::Mem ConstantPool::splat(uint32_t bits) {
    auto it = splats_.find(bits);
    if (it != splats_.end()) return x86::ymmword_ptr(label_, int32_t(it->second));
    const uint32_t off = uint32_t(words_.size() * 4);
    words_.insert(words_.end(), 8, bits);
    splats_[bits] = off;
    return x86::ymmword_ptr(label_, int32_t(off));
}

x86::Mem ConstantPool::vector(const uint32_t v[8]) {
    const uint32_t off = uint32_t(words_.size() * 4);
    words_.insert(words_.end(), v, v + 8);
    return x86::ymmword_ptr(label_, int32_t(off));
}

void ConstantPool::emit(x86::Assembler& a) const {
    a.align(AlignMode::kData, 32);
    a.bind(label_);
    if (!words_.empty()) a.embed(words_.data(), words_.size() * 4);
}

// --- next uses --------------------------------------------------------------------------------------------------

void segment_uses(const ProgramImpl& p, size_t first, size_t end, std::vector<Uses>& uses) {
    uses.assign(end - first, Uses{});
    std::unordered_map<uint64_t, uint32_t> next;  // value -> position of its next read
    auto lookup = [&](uint64_t k) {
        auto it = next.find(k);
        return it == next.end() ? kNever : it->second;
    };
    for (size_t i = end; i-- > first;) {
        const Inst& in = p.code[i];
        Uses& u = uses[i - first];
        auto add = [&](uint64_t k, bool write) {
            for (int j = 0; j < u.n; ++j)
                if (u.key[j] == k && u.write[j] == write) return;
            if (u.n < Uses::kMax) u.key[u.n] = k, u.write[u.n] = write, u.next[u.n] = 0, ++u.n;
        };
        // the values this instruction reads and writes (footprint, plus the local words of the fixed accesses)
        const Footprint f = footprint(in);
        for (int k = 0; k < f.num_reads && k < Footprint::kMax; ++k) add(reg_key(f.reads[k]), false);
        for (int k = 0; k < f.num_writes && k < Footprint::kMax; ++k) add(reg_key(f.writes[k]), true);
        if (in.op == Op::LoadLocalFixed || in.op == Op::StoreLocalFixed) add(word_key(in.imm), false);
        if (in.op == Op::StoreLocalFixed) add(word_key(in.imm), true);
        // writes first (backwards: they end the previous value), then reads
        for (int k = 0; k < u.n; ++k)
            if (u.write[k]) {
                u.next[k] = lookup(u.key[k]);
                next.erase(u.key[k]);
            }
        for (int k = 0; k < u.n; ++k)
            if (!u.write[k]) {
                u.next[k] = lookup(u.key[k]);
                next[u.key[k]] = uint32_t(i);
            }
    }
}

// --- register allocation ----------------------------------------------------------------------------------------

LaneEmitter::LaneEmitter(const ProgramImpl& p, const Analysis& an, x86::Assembler& a, ConstantPool& pool)
    : p_(p), an_(an), a_(a), pool_(pool), inline_gallivm_(gallivm::avx2_build_runs()) {
    reg_where_.assign(p.num_regs, -1);
    known_.assign(p.num_regs, 0);
    known_bits_.assign(p.num_regs, 0);
    word_where_.assign(std::max(1u, p.local_words), -1);
}

x86::Mem LaneEmitter::home(uint64_t key) const {
    const uint32_t index = uint32_t(key);
    const int32_t off = int32_t(size_t(index) * kLanes * 4 + size_t(half_) * 32);
    return x86::ymmword_ptr((key >> 32) == 1 ? kRegsBase : kLocalBase, off);
}

int8_t& LaneEmitter::where(uint64_t key) {
    return (key >> 32) == 1 ? reg_where_[uint32_t(key)] : word_where_[uint32_t(key)];
}

uint32_t LaneEmitter::next_use(uint64_t key, bool write) const {
    for (int k = 0; k < uses_->n; ++k)
        if (uses_->key[k] == key && uses_->write[k] == write) return uses_->next[k];
    return 0;  // not listed: keep it (never happens for the ops emitted here)
}

int LaneEmitter::alloc() {
    int victim = -1;
    for (int i = 0; i < 16; ++i) {
        if (phys_[i].pinned) continue;
        if (phys_[i].key == 0) return i;
        if (victim < 0 || phys_[i].next > phys_[victim].next) victim = i;
    }
    if (victim < 0) {  // every register pinned by one instruction: no lowering needs that many
        overflow_ = true;
        return 0;
    }
    Phys& v = phys_[victim];
    // a local register read again must survive in its home; everything else is there already
    if (v.next != kNever && (v.key >> 32) == 1 && an_.local[uint32_t(v.key)]) a_.vmovups(home(v.key), x86::ymm(victim));
    where(v.key) = -1;
    v.key = 0;
    return victim;
}

x86::Ymm LaneEmitter::use(uint64_t key) {
    int p = where(key);
    if (p < 0) {
        p = alloc();
        const bool known = (key >> 32) == 1 && known_[uint32_t(key)];
        a_.vmovups(x86::ymm(p), known ? pool_.splat(known_bits_[uint32_t(key)]) : home(key));
        phys_[p].key = key;
        where(key) = int8_t(p);
    }
    phys_[p].pinned = true;
    phys_[p].next = next_use(key, false);
    return x86::ymm(p);
}

// The value in a register this instruction may overwrite: its own register when this is its last read here (no
// copy), else a copy.
x86::Ymm LaneEmitter::take(uint64_t key) {
    Ymm y = use(key);
    const int p = int(y.id());
    if (phys_[p].next == kNever) {
        where(key) = -1;
        phys_[p].key = 0;
        return y;
    }
    Ymm d = temp();
    a_.vmovaps(d, y);
    return d;
}

x86::Ymm LaneEmitter::temp() {
    const int p = alloc();
    phys_[p].pinned = true;
    phys_[p].key = 0;
    return x86::ymm(p);
}

void LaneEmitter::def(uint64_t key, Ymm y) {
    const int p = int(y.id());
    int8_t& w = where(key);
    if (w >= 0 && w != p) phys_[w].key = 0;  // the old value (maybe an operand of this instruction) is gone
    if ((key >> 32) == 1) forget_value(uint32_t(key));
    w = int8_t(p);
    phys_[p].key = key;
    phys_[p].next = next_use(key, true);
    const bool is_reg = (key >> 32) == 1;
    if (!is_reg || !an_.local[uint32_t(key)]) a_.vmovups(home(key), y);  // write through
}

void LaneEmitter::end_instruction() {
    for (Phys& ph : phys_) {
        ph.pinned = false;
        if (ph.key != 0 && ph.next == kNever) {  // dead here, or valid only in its home from now on
            where(ph.key) = -1;
            ph.key = 0;
        }
    }
}

bool LaneEmitter::pass(size_t first, size_t end, const std::vector<Uses>& uses, int h) {
    half_ = h;
    uniform_slot_ = kNoReg;  // the code before this pass (a sync op, the other half's end) may use r8-r11
    for (uint32_t r : known_list_) known_[r] = 0;  // folded values live within one pass
    known_list_.clear();
    for (size_t i = first; i < end; ++i) {
        uses_ = &uses[i - first];
        const Inst& in = p_.code[i];
        if (dead(in)) {  // its results' old values (maybe its own operands) are gone all the same
            for (int k = 0; k < uses_->n; ++k) {
                if (!uses_->write[k]) continue;
                if ((uses_->key[k] >> 32) == 1) forget_value(uint32_t(uses_->key[k]));
                if (where(uses_->key[k]) >= 0) {
                    phys_[where(uses_->key[k])] = Phys{};
                    where(uses_->key[k]) = -1;
                }
            }
            end_instruction();
            continue;
        }
        if (fold(in)) {
            end_instruction();
            continue;
        }
        if (!(in.op == Op::LoadShared ? load_shared(in) : op(in)) || overflow_) return false;
        end_instruction();
    }
    for (Phys& ph : phys_) {
        if (ph.key != 0) where(ph.key) = -1;
        ph = Phys{};
    }
    return true;
}

// Whether every result of `in` is a segment-local register that nothing reads before the segment ends or writes
// it again: such a value would never leave its YMM register (def() does not write local registers through, and
// alloc() spills only values read later), so nothing can see it and the instruction is not emitted. Lane-wise ops
// write nothing but their results (memory writes are sync ops); an op whose footprint lists more writes than its
// Uses entry holds, or that writes a local word, is emitted. E.g. meshes_lit's shader loads the push constant's
// whole vec4 and reads three words.
bool LaneEmitter::dead(const Inst& in) const {
    const Footprint f = footprint(in);
    if (f.num_writes == 0 || f.num_writes > Footprint::kMax) return false;
    int found = 0;
    for (int k = 0; k < uses_->n; ++k) {
        if (!uses_->write[k]) continue;
        const uint64_t key = uses_->key[k];
        if ((key >> 32) != 1 || !an_.local[uint32_t(key)] || uses_->next[k] != kNever) return false;
        ++found;
    }
    return found == f.num_writes;
}

// --- lowerings --------------------------------------------------------------------------------------------------

template <typename F>
void LaneEmitter::unary(const Inst& in, F f) {
    Ymm a = use(in.a), d = temp();
    f(d, a);
    def(in.d, d);
}

template <typename F>
void LaneEmitter::binary(const Inst& in, F f) {
    Ymm a = use(in.a), b = use(in.b), d = temp();
    f(d, a, b);
    def(in.d, d);
}

void LaneEmitter::fcmp(const Inst& in, uint32_t predicate) {
    binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vcmpps(d, a, b, predicate); });
}

// (m & x) | (~m & y), bitwise: m need not be a clean mask
x86::Ymm LaneEmitter::select(Ymm m, Ymm x, Ymm y) {
    Ymm t = temp(), d = temp();
    a_.vpand(t, m, x);
    a_.vpandn(d, m, y);
    a_.vpor(d, d, t);
    return d;
}

// exec.cpp min_f / max_f: (a < b || b != b) ? a : b, (a > b || b != b) ? a : b
x86::Ymm LaneEmitter::fmin(Ymm a, Ymm b) {
    Ymm m = temp(), n = temp(), d = temp();
    a_.vcmpps(m, a, b, kLtOQ);
    a_.vcmpps(n, b, b, kUnordQ);
    a_.vorps(m, m, n);
    a_.vblendvps(d, b, a, m);
    return d;
}

x86::Ymm LaneEmitter::fmax(Ymm a, Ymm b) {
    Ymm m = temp(), n = temp(), d = temp();
    a_.vcmpps(m, a, b, kGtOQ);
    a_.vcmpps(n, b, b, kUnordQ);
    a_.vorps(m, m, n);
    a_.vblendvps(d, b, a, m);
    return d;
}

x86::Ymm LaneEmitter::round(Ymm a, uint32_t mode) {
    Ymm d = temp();
    a_.vroundps(d, a, mode);
    return d;
}

// FAdd / FMul with the interpreter's operand order, for the NaN it returns when both are NaN (analysis.h
// nan_order). The order may differ between the two quarters of this half: then vblendps swaps the operands in the
// quarters where b comes first (the same IEEE operation lane for lane, a + b and b + a differ only in that NaN).
void LaneEmitter::add_mul(const Inst& in) {
    const NanOrder lo = nan_order(in.op, 2 * half_), hi = nan_order(in.op, 2 * half_ + 1);
    const bool add = in.op == Op::FAdd;
    const bool free = nan_order_free(in);
    binary(in, [&](Ymm d, Ymm a, Ymm b) {
        Ymm x = a, y = b;
        if (lo != hi && !free) {
            const uint32_t b_first = lo == NanOrder::BFirst ? 0x0Fu : 0xF0u;  // the lanes of the b-first quarter
            x = temp(), y = temp();
            a_.vblendps(x, a, b, b_first);
            a_.vblendps(y, b, a, b_first);
        } else if (lo == NanOrder::BFirst) {
            std::swap(x, y);
        }
        if (add)
            a_.vaddps(d, x, y);
        else
            a_.vmulps(d, x, y);
    });
}

// x > y signed (unsigned: both biased by 2^31); Lt swaps the operands; Le / Ge negate Gt / Lt
void LaneEmitter::int_compare(const Inst& in) {
    const Op op = in.op;
    const bool is_unsigned = op == Op::UGt || op == Op::ULt || op == Op::ULe || op == Op::UGe;
    const bool swap = op == Op::SLt || op == Op::SGe || op == Op::ULt || op == Op::UGe;
    const bool negate = op == Op::SLe || op == Op::SGe || op == Op::ULe || op == Op::UGe;
    Ymm a = use(in.a), b = use(in.b), d = temp();
    if (is_unsigned) {
        Ymm ua = temp(), ub = temp();
        a_.vpxor(ua, a, pool_.splat(0x80000000u));
        a_.vpxor(ub, b, pool_.splat(0x80000000u));
        a = ua, b = ub;
    }
    a_.vpcmpgtd(d, swap ? b : a, swap ? a : b);
    if (negate) a_.vpxor(d, d, pool_.splat(~0u));
    def(in.d, d);
}

// exec_kernels.h f2u: x in (-1, 2^32) truncates (cvttps2dq covers [0, 2^31); [2^31, 2^32) is converted from
// x - 2^31, exact there, with the top bit put back); outside or NaN all ones, as lavapipe.
void LaneEmitter::f2u(const Inst& in) {
    Ymm a = use(in.a), big = temp(), t = temp(), m = temp();
    a_.vcmpps(big, a, pool_.splat(fbits(2147483648.0f)), kGeOQ);
    a_.vandps(t, big, pool_.splat(fbits(2147483648.0f)));
    a_.vsubps(t, a, t);
    a_.vcvttps2dq(t, t);
    a_.vpand(big, big, pool_.splat(0x80000000u));
    a_.vpxor(t, t, big);
    a_.vcmpps(m, a, pool_.splat(fbits(-1.0f)), kGtOQ);
    a_.vcmpps(big, a, pool_.splat(fbits(4294967296.0f)), kLtOQ);
    a_.vpand(m, m, big);
    a_.vpxor(m, m, pool_.splat(~0u));
    a_.vpor(t, t, m);
    def(in.d, t);
}

// float(uint32): both 16-bit halves convert exactly, hi * 65536 is exact, the one addition rounds once.
void LaneEmitter::u2f(const Inst& in) {
    Ymm a = use(in.a), hi = temp(), lo = temp();
    a_.vpsrld(hi, a, 16);
    a_.vpand(lo, a, pool_.splat(0xFFFFu));
    a_.vcvtdq2ps(hi, hi);
    a_.vcvtdq2ps(lo, lo);
    a_.vmulps(hi, hi, pool_.splat(fbits(65536.0f)));
    a_.vaddps(hi, hi, lo);
    def(in.d, hi);
}

// x > 0 ? 1 : x < 0 ? -1 : x * 0
void LaneEmitter::fsign(const Inst& in) {
    Ymm a = use(in.a), zero = temp(), gt = temp(), lt = temp(), d = temp();
    a_.vxorps(zero, zero, zero);
    a_.vcmpps(gt, a, zero, kGtOQ);
    a_.vcmpps(lt, a, zero, kLtOQ);
    a_.vmulps(d, a, zero);
    a_.vblendvps(d, d, pool_.splat(fbits(-1.0f)), lt);
    a_.vblendvps(d, d, pool_.splat(fbits(1.0f)), gt);
    def(in.d, d);
}

// t = clamp((x - e0) / (e1 - e0), 0, 1); t * t * (3 - 2 * t)
void LaneEmitter::smooth_step(const Inst& in) {
    Ymm a = use(in.a), b = use(in.b), c = use(in.c), num = temp(), den = temp(), k = temp();
    a_.vsubps(num, c, a);
    a_.vsubps(den, b, a);
    a_.vdivps(num, num, den);
    a_.vxorps(k, k, k);
    Ymm t = fmax(num, k);
    a_.vmovups(k, pool_.splat(fbits(1.0f)));
    t = fmin(t, k);
    Ymm tt = temp(), s = temp();
    a_.vmulps(tt, t, t);
    a_.vmovups(k, pool_.splat(fbits(2.0f)));
    a_.vmulps(s, k, t);
    a_.vmovups(k, pool_.splat(fbits(3.0f)));
    a_.vsubps(s, k, s);
    a_.vmulps(tt, tt, s);
    def(in.d, tt);
}

// Quad neighbours within each 128-bit lane: lane = quad * 4 + (y & 1) * 2 + (x & 1).
void LaneEmitter::derivative(const Inst& in, uint32_t right, uint32_t left) {
    Ymm a = use(in.a), r = temp(), l = temp();
    a_.vshufps(r, a, a, right);
    a_.vshufps(l, a, a, left);
    a_.vsubps(r, r, l);
    def(in.d, r);
}

// d = local[min(imm + a, n - 1)] per lane: a gather from word (imm + umin(a, n - 1 - imm)) * 16 + lane.
bool LaneEmitter::load_local(const Inst& in) {
    const uint64_t words = std::max(1u, p_.local_words);
    if (in.n == 0 || in.n > words) return false;
    if (in.imm >= in.n - 1) {  // every index clamps to the last word
        def(in.d, take(word_key(in.n - 1)));
        return true;
    }
    static const uint32_t kLaneIds[2][8] = {{0, 1, 2, 3, 4, 5, 6, 7}, {8, 9, 10, 11, 12, 13, 14, 15}};
    Ymm a = use(in.a), idx = temp(), mask = temp(), d = temp();
    a_.vpminud(idx, a, pool_.splat(in.n - 1 - in.imm));
    a_.vpaddd(idx, idx, pool_.splat(in.imm));
    a_.vpslld(idx, idx, 4);
    a_.vpaddd(idx, idx, pool_.vector(kLaneIds[half_]));
    a_.vpcmpeqd(mask, mask, mask);
    a_.vpxor(d, d, d);
    a_.vpgatherdd(d, x86::ptr(kLocalBase, idx, 2), mask);
    def(in.d, d);
    return true;
}

// d = fn(a, b) for this half's eight lanes, in their homes (helpers.h LaneFn): a libm op without leaving the
// segment. The call clobbers every YMM register, so first the values this segment still reads go to their homes
// (only segment-local registers can be missing there: everything else is written through) and the machine
// registers are emptied; the result is left in d's home, where the next read finds it.
void LaneEmitter::lane_call(const Inst& in, const void* fn) {
    for (uint32_t r : {in.a, in.b})  // a folded operand has no home value yet: to a machine register, spilled below
        if (r < known_.size() && known_[r]) use(r);
    for (int i = 0; i < 16; ++i) {
        Phys& ph = phys_[i];
        if (ph.key == 0) continue;
        const bool is_reg = (ph.key >> 32) == 1;
        const uint32_t r = uint32_t(ph.key);
        // a local operand (the callee reads it from its home), or a local value read later that the call keeps
        const bool operand = is_reg && (r == in.a || r == in.b);
        if (is_reg && an_.local[r] && (operand || (ph.next != kNever && r != in.d)))
            a_.vmovups(home(ph.key), x86::ymm(i));
        where(ph.key) = -1;
        ph = Phys{};
    }
    using namespace x86;
    auto address = [&](uint32_t r) { return ptr(kRegsBase, int32_t(size_t(r) * kLanes * 4 + size_t(half_) * 32)); };
    a_.lea(rdi, address(in.d));
    a_.lea(rsi, address(in.a));
    a_.lea(rdx, address(in.b == kNoReg ? in.a : in.b));
    a_.mov(rax, reinterpret_cast<uint64_t>(fn));
    a_.vzeroupper();
    a_.call(rax);
    uniform_slot_ = kNoReg;  // the call clobbered r8-r11 (load_buf_uniform)
    forget_value(in.d);
}

// The op families below mirror shader/exec_kernels.h; each answers nullopt for an op not of its family, else
// whether the op was emitted (false: refused, e.g. a fixed local word out of range).

// Float arithmetic, rounding and the GLSL.std.450 float functions emitted inline.
std::optional<bool> LaneEmitter::float_op(const Inst& in) {
    switch (in.op) {
        case Op::FAdd:
        case Op::FMul:
            add_mul(in);
            return true;
        case Op::FSub:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vsubps(d, a, b); });
            return true;
        case Op::FDiv:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vdivps(d, a, b); });
            return true;
        case Op::FNeg:
            unary(in, [&](Ymm d, Ymm a) { a_.vpxor(d, a, pool_.splat(0x80000000u)); });
            return true;
        case Op::FAbs:
            unary(in, [&](Ymm d, Ymm a) { a_.vpand(d, a, pool_.splat(0x7fffffffu)); });
            return true;
        case Op::FMin:
            def(in.d, fmin(use(in.a), use(in.b)));
            return true;
        case Op::FMax:
            def(in.d, fmax(use(in.a), use(in.b)));
            return true;
        case Op::FMod: {  // a - b * floor(a / b)
            Ymm a = use(in.a), b = use(in.b), q = temp();
            a_.vdivps(q, a, b);
            a_.vroundps(q, q, kFloor);
            a_.vmulps(q, b, q);
            a_.vsubps(q, a, q);
            def(in.d, q);
            return true;
        }
        case Op::Fma: {  // std::fma: one rounding
            Ymm a = use(in.a), b = use(in.b), c = use(in.c), d = temp();
            a_.vmovaps(d, a);
            a_.vfmadd213ps(d, b, c);
            def(in.d, d);
            return true;
        }
        case Op::Floor:
            def(in.d, round(use(in.a), kFloor));
            return true;
        case Op::Ceil:
            def(in.d, round(use(in.a), kCeil));
            return true;
        case Op::Trunc:
            def(in.d, round(use(in.a), kTrunc));
            return true;
        case Op::Round:
        case Op::RoundEven:
            def(in.d, round(use(in.a), kNearby));
            return true;
        case Op::Fract:  // x - floor(x)
            unary(in, [&](Ymm d, Ymm a) {
                a_.vroundps(d, a, kFloor);
                a_.vsubps(d, a, d);
            });
            return true;
        case Op::FSign:
            fsign(in);
            return true;
        case Op::Sqrt:
            unary(in, [&](Ymm d, Ymm a) { a_.vsqrtps(d, a); });
            return true;
        case Op::InvSqrt:  // 1 / sqrt(x), both exact IEEE
            unary(in, [&](Ymm d, Ymm a) {
                Ymm one = temp();
                a_.vsqrtps(d, a);
                a_.vmovups(one, pool_.splat(fbits(1.0f)));
                a_.vdivps(d, one, d);
            });
            return true;
        case Op::FClamp:  // min(max(x, lo), hi)
            def(in.d, fmin(fmax(use(in.a), use(in.b)), use(in.c)));
            return true;
        case Op::Step:  // step(edge a, x b) = b < a ? 0 : 1
            binary(in, [&](Ymm d, Ymm a, Ymm b) {
                a_.vcmpps(d, b, a, kLtOQ);
                a_.vandnps(d, d, pool_.splat(fbits(1.0f)));
            });
            return true;
        case Op::SmoothStep:
            smooth_step(in);
            return true;
        default:
            return std::nullopt;
    }
}

// Compares (float ordered/unordered, integer), the NaN/Inf tests and the selects.
std::optional<bool> LaneEmitter::compare_op(const Inst& in) {
    switch (in.op) {
        case Op::Select:
            def(in.d, select(use(in.c), use(in.a), use(in.b)));
            return true;
        case Op::MaskedMov:
            def(in.d, select(use(in.c), use(in.a), use(in.d)));
            return true;
        case Op::FOrdEq:
            fcmp(in, kEqOQ);
            return true;
        case Op::FOrdNe:
            fcmp(in, kNeqOQ);
            return true;
        case Op::FOrdLt:
            fcmp(in, kLtOS);
            return true;
        case Op::FOrdLe:
            fcmp(in, kLeOS);
            return true;
        case Op::FOrdGt:
            fcmp(in, kGtOS);
            return true;
        case Op::FOrdGe:
            fcmp(in, kGeOS);
            return true;
        case Op::FUnordEq:
            fcmp(in, kEqUQ);
            return true;
        case Op::FUnordNe:
            fcmp(in, kNeqUQ);
            return true;
        case Op::FUnordLt:
            fcmp(in, kNgeUS);
            return true;
        case Op::FUnordLe:
            fcmp(in, kNgtUS);
            return true;
        case Op::FUnordGt:
            fcmp(in, kNleUS);
            return true;
        case Op::FUnordGe:
            fcmp(in, kNltUS);
            return true;
        case Op::IsNan:  // |x|'s bits above the infinity pattern
            unary(in, [&](Ymm d, Ymm a) {
                a_.vpand(d, a, pool_.splat(0x7fffffffu));
                a_.vpcmpgtd(d, d, pool_.splat(0x7f800000u));
            });
            return true;
        case Op::IsInf:
            unary(in, [&](Ymm d, Ymm a) {
                a_.vpand(d, a, pool_.splat(0x7fffffffu));
                a_.vpcmpeqd(d, d, pool_.splat(0x7f800000u));
            });
            return true;
        case Op::IEq:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpcmpeqd(d, a, b); });
            return true;
        case Op::INe:
            binary(in, [&](Ymm d, Ymm a, Ymm b) {
                a_.vpcmpeqd(d, a, b);
                a_.vpxor(d, d, pool_.splat(~0u));
            });
            return true;
        case Op::SGt:
        case Op::SLt:
        case Op::SLe:
        case Op::SGe:
        case Op::UGt:
        case Op::ULt:
        case Op::ULe:
        case Op::UGe:
            int_compare(in);
            return true;
        default:
            return std::nullopt;
    }
}

// Integer arithmetic, bitwise ops, shifts (count mod 32) and integer min/max/abs.
std::optional<bool> LaneEmitter::int_op(const Inst& in) {
    switch (in.op) {
        case Op::IAdd:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpaddd(d, a, b); });
            return true;
        case Op::ISub:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpsubd(d, a, b); });
            return true;
        case Op::IMul:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpmulld(d, a, b); });
            return true;
        case Op::INeg:
            unary(in, [&](Ymm d, Ymm a) {
                a_.vpxor(d, d, d);
                a_.vpsubd(d, d, a);
            });
            return true;
        case Op::And:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpand(d, a, b); });
            return true;
        case Op::Or:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpor(d, a, b); });
            return true;
        case Op::Xor:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpxor(d, a, b); });
            return true;
        case Op::Not:
            unary(in, [&](Ymm d, Ymm a) { a_.vpxor(d, a, pool_.splat(~0u)); });
            return true;
        case Op::Shl:
        case Op::ShrL:
        case Op::ShrA: {  // the count is taken mod 32
            const Op op = in.op;
            binary(in, [&](Ymm d, Ymm a, Ymm b) {
                a_.vpand(d, b, pool_.splat(31));
                if (op == Op::Shl)
                    a_.vpsllvd(d, a, d);
                else if (op == Op::ShrL)
                    a_.vpsrlvd(d, a, d);
                else
                    a_.vpsravd(d, a, d);
            });
            return true;
        }
        case Op::SMin:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpminsd(d, a, b); });
            return true;
        case Op::SMax:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpmaxsd(d, a, b); });
            return true;
        case Op::UMin:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpminud(d, a, b); });
            return true;
        case Op::UMax:
            binary(in, [&](Ymm d, Ymm a, Ymm b) { a_.vpmaxud(d, a, b); });
            return true;
        case Op::SAbs:
            unary(in, [&](Ymm d, Ymm a) { a_.vpabsd(d, a); });
            return true;
        default:
            return std::nullopt;
    }
}

// Float <-> integer conversions and the quad derivatives.
std::optional<bool> LaneEmitter::convert_op(const Inst& in) {
    switch (in.op) {
        case Op::F2S:  // out of range and NaN give INT32_MIN, which is what cvttps2dq gives
            unary(in, [&](Ymm d, Ymm a) { a_.vcvttps2dq(d, a); });
            return true;
        case Op::F2U:
            f2u(in);
            return true;
        case Op::S2F:
            unary(in, [&](Ymm d, Ymm a) { a_.vcvtdq2ps(d, a); });
            return true;
        case Op::U2F:
            u2f(in);
            return true;
        case Op::DdxFine:  // right - left of the lane's row: lanes {1,1,3,3} - {0,0,2,2} of each quad
            derivative(in, 0xF5, 0xA0);
            return true;
        case Op::DdyFine:  // bottom - top of the lane's column: {2,3,2,3} - {0,1,0,1}
            derivative(in, 0xEE, 0x44);
            return true;
        case Op::DdxCoarse:  // the quad's top row: {1,1,1,1} - {0,0,0,0}
            derivative(in, 0x55, 0x00);
            return true;
        case Op::DdyCoarse:  // the quad's left column: {2,2,2,2} - {0,0,0,0}
            derivative(in, 0xAA, 0x00);
            return true;
        default:
            return std::nullopt;
    }
}

// Moves, local memory, buffer loads and the live mask.
std::optional<bool> LaneEmitter::memory_op(const Inst& in) {
    switch (in.op) {
        case Op::Mov:
            def(in.d, take(reg_key(in.a)));
            return true;
        case Op::LoadLocal:
            return load_local(in);
        case Op::LoadLocalFixed:
            if (in.imm >= std::max(1u, p_.local_words)) return false;
            def(in.d, take(word_key(in.imm)));
            return true;
        case Op::StoreLocalFixed:
            if (in.imm >= std::max(1u, p_.local_words)) return false;
            def(word_key(in.imm), select(use(in.c), use(in.b), use(word_key(in.imm))));
            return true;
        case Op::LoadBufUniform:
            load_buf_uniform(in);
            return true;
        case Op::LoadBuf:
            load_buf(in);
            return true;
        case Op::Kill: {  // live &= ~a
            Ymm a = use(in.a), live = use(in.d), d = temp();
            a_.vpandn(d, a, live);
            def(in.d, d);
            return true;
        }
        default:
            return std::nullopt;
    }
}

bool LaneEmitter::op(const Inst& in) {
    if (const std::optional<bool> emitted = gallivm_op(in)) return *emitted;
    if (const LaneFn f = lane_function(in.op)) {  // libm, as the interpreter calls it
        lane_call(in, reinterpret_cast<const void*>(f));
        return true;
    }
    for (auto family : {&LaneEmitter::float_op, &LaneEmitter::compare_op, &LaneEmitter::int_op,
                        &LaneEmitter::convert_op, &LaneEmitter::memory_op})
        if (const std::optional<bool> emitted = (this->*family)(in)) return *emitted;
    return false;
}

}  // namespace tilevk::shader::jit
