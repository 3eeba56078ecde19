// Code generation: one IR program -> one native function (asmjit's x86::Assembler, AVX2/FMA). This file lays out
// the function, its control flow and the calls into the interpreter; lanes.cpp emits the lane-wise segments in
// between, once per 8-lane half (codegen.h has the machine state).
#include <asmjit/x86.h>

#include <chrono>
#include <climits>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "shader/jit/analysis.h"
#include "shader/jit/codegen.h"
#include "shader/jit/helpers.h"
#include "shader/jit/jit.h"

namespace tilevk::shader::jit {

namespace {

using namespace asmjit;

JitRuntime& runtime() {
    static JitRuntime* rt = new JitRuntime();  // never destroyed: programs may outlive static destruction
    return *rt;
}

class ErrorCollector : public ErrorHandler {
  public:
    Error error = kErrorOk;
    std::string message;
    void handleError(Error err, const char* msg, BaseEmitter*) override {
        if (error == kErrorOk) {
            error = err;
            message = msg;
        }
    }
};

class Generator {
  public:
    Generator(const ProgramImpl& p, const Analysis& an, x86::Assembler& a, Code& out)
        : p_(p), an_(an), a_(a), out_(out), pool_(a.newLabel()), lanes_(p, an, a, pool_) {}

    // Emits the whole function; false with *why set when something cannot be compiled.
    bool generate(std::string* why);

  private:
    x86::Mem home(uint32_t r, int half) const {
        return x86::ymmword_ptr(kRegsBase, int32_t(size_t(r) * kLanes * 4 + size_t(half) * 32));
    }
    void any_lane(uint32_t r);  // ZF = no lane of r set
    void resume_table();        // the jump from Frame::resume to the instruction after its Barrier
    void call(const void* fn, const Inst* code, int64_t index = -1);
    bool sync(const Inst& in);

    const ProgramImpl& p_;
    const Analysis& an_;
    x86::Assembler& a_;
    Code& out_;
    ConstantPool pool_;
    LaneEmitter lanes_;
    std::vector<Label> labels_;
    Label exit_, return_, loop_limit_;
    size_t helpers_used_ = 0;
};

void Generator::any_lane(uint32_t r) {
    a_.vmovups(x86::ymm0, home(r, 0));
    a_.vpor(x86::ymm0, x86::ymm0, home(r, 1));
    a_.vptest(x86::ymm0, x86::ymm0);
}

// A program with barriers runs in phases (exec.cpp run_workgroup): a run that starts at the pc after a Barrier jumps
// to that instruction's label (analyze() makes one there). Barriers are few, so a chain of compares does.
void Generator::resume_table() {
    if (!p_.has_barrier) return;
    a_.mov(x86::rax, x86::qword_ptr(kFrameBase, int32_t(offsetof(Frame, resume))));
    for (size_t pc = 0; pc < p_.code.size(); ++pc) {
        if (p_.code[pc].op != Op::Barrier) continue;
        a_.cmp(x86::rax, int32_t(pc + 1));
        a_.je(labels_[pc + 1]);
    }
}

// fn(frame->scratch, code[, index]): every YMM register is free here (a sync point) and the callee-saved bases
// survive.
void Generator::call(const void* fn, const Inst* code, int64_t index) {
    a_.mov(x86::rdi, x86::qword_ptr(kFrameBase, int32_t(offsetof(Frame, scratch))));
    if (code) a_.mov(x86::rsi, reinterpret_cast<uint64_t>(code));
    if (index >= 0) a_.mov(x86::edx, uint32_t(index));
    a_.mov(x86::rax, reinterpret_cast<uint64_t>(fn));
    a_.call(x86::rax);
}

// Control flow and helper ops: they read whole registers from their homes.
bool Generator::sync(const Inst& in) {
    switch (in.op) {
        case Op::Jump:
            a_.jmp(labels_[in.imm]);
            return true;
        case Op::JumpIfNone:
            any_lane(in.a);
            a_.jz(labels_[in.imm]);
            return true;
        case Op::JumpIfAny: {
            // Loop back while any lane continues. The watchdog as exec.cpp: with a stop flag, leave once it is
            // set; without one, leave after kMaxLoopBackEdges back edges.
            Label stay = a_.newLabel(), count = a_.newLabel();
            any_lane(in.a);
            a_.jz(stay);
            a_.mov(x86::rax, x86::qword_ptr(kFrameBase, int32_t(offsetof(Frame, stop))));
            a_.test(x86::rax, x86::rax);
            a_.jz(count);
            a_.cmp(x86::byte_ptr(x86::rax), 0);
            a_.jne(loop_limit_);
            a_.jmp(labels_[in.imm]);
            a_.bind(count);
            const x86::Mem edges = x86::qword_ptr(kFrameBase, int32_t(offsetof(Frame, back_edges)));
            a_.inc(edges);
            a_.cmp(edges, int32_t(kMaxLoopBackEdges));
            a_.ja(loop_limit_);
            a_.jmp(labels_[in.imm]);
            a_.bind(stay);
            return true;
        }
        case Op::Halt:
            a_.jmp(exit_);
            return true;
        case Op::Barrier:  // every value is in its home (a sync point): return where the next phase resumes
            a_.mov(x86::rax, uint64_t(&in - p_.code.data()) + 1);
            a_.jmp(return_);
            return true;
        case Op::StoreShared:
            return emit_store_shared(a_, p_, in);
        case Op::AtomicShared:
            return emit_atomic_shared(a_, p_, in);
        case Op::StoreBuf:
            if (lowering(in) == Lowering::Native) return emit_store_buf(a_, p_, in);
            break;
        default:
            break;
    }
    if (lowering(in) != Lowering::Helper) return false;
    // the interpreter's code for this one instruction: the instruction and a Halt, run by execute_code
    Inst* code = out_.helper_code.get() + 2 * helpers_used_++;
    code[0] = in;
    code[1] = Inst{Op::Halt};
    if (in.op == Op::Sample)
        call(reinterpret_cast<const void*>(&run_sample), code, int64_t(out_.sample_ops++));
    else
        call(reinterpret_cast<const void*>(&run_one_instruction), code);
    ++out_.helper_ops;
    return true;
}

bool Generator::generate(std::string* why) {
    const size_t n = p_.code.size();
    if (size_t(p_.num_regs) * kLanes * 4 > INT32_MAX || size_t(p_.local_words) * kLanes * 4 > INT32_MAX) {
        *why = "the register file or local memory is too large for 32-bit displacements";
        return false;
    }
    size_t helpers = 0;
    for (const Inst& in : p_.code) helpers += lowering(in) == Lowering::Helper;
    out_.helper_code = std::make_unique<Inst[]>(std::max<size_t>(1, 2 * helpers));
    labels_.resize(n + 1);
    for (size_t i = 0; i <= n; ++i)
        if (an_.label[i]) labels_[i] = a_.newLabel();
    exit_ = a_.newLabel();
    return_ = a_.newLabel();
    loop_limit_ = a_.newLabel();
    if (size_t(p_.shared_words) * 4 > INT32_MAX) {
        *why = "the shared memory is too large for 32-bit displacements";
        return false;
    }

    // void entry(Frame* rdi): save the callee-saved registers used as bases; rsp stays 16-byte aligned for calls
    using namespace x86;
    a_.push(rbp);
    a_.mov(rbp, rsp);
    a_.push(rbx);
    a_.push(r12);
    a_.push(r13);
    a_.push(r14);  // five pushes after the return address: rsp is 16-byte aligned again
    a_.mov(kFrameBase, rdi);
    a_.mov(kRegsBase, qword_ptr(rdi, int32_t(offsetof(Frame, regs))));
    a_.mov(kLocalBase, qword_ptr(rdi, int32_t(offsetof(Frame, local))));
    a_.mov(kSlotsBase, qword_ptr(rdi, int32_t(offsetof(Frame, slots))));
    resume_table();

    std::vector<Uses> uses;
    for (size_t pc = 0; pc < n;) {
        if (an_.label[pc]) a_.bind(labels_[pc]);
        const Inst& in = p_.code[pc];
        if (is_sync(in)) {
            if (!sync(in)) {
                *why = "IR op " + op_name(in.op) + " at " + std::to_string(pc) + " is not compiled";
                return false;
            }
            ++pc;
            continue;
        }
        size_t end = pc + 1;
        while (end < n && an_.segment[end] == an_.segment[pc]) ++end;
        segment_uses(p_, pc, end, uses);
        for (int h = 0; h < 2; ++h)
            if (!lanes_.pass(pc, end, uses, h)) {
                *why = "a lane-wise op in [" + std::to_string(pc) + ", " + std::to_string(end) + ") is not compiled";
                return false;
            }
        out_.native_ops += uint32_t(end - pc);
        out_.folded = lanes_.folded();
        pc = end;
    }
    if (an_.label[n]) a_.bind(labels_[n]);
    for (const Inst& in : p_.code) out_.native_ops += is_sync(in) && lowering(in) == Lowering::Native;

    a_.bind(exit_);
    a_.mov(rax, uint64_t(kRunDone));
    a_.bind(return_);
    a_.vzeroupper();
    a_.pop(r14);
    a_.pop(r13);
    a_.pop(r12);
    a_.pop(rbx);
    a_.pop(rbp);
    a_.ret();

    // The watchdog stopped the run: count it where Scratch::loop_limit_hits reads it, leave.
    a_.bind(loop_limit_);
    call(reinterpret_cast<const void*>(&count_loop_limit_hit), nullptr);
    a_.jmp(exit_);
    pool_.emit(a_);
    return true;
}

}  // namespace

Code::~Code() {
    if (entry) runtime().release(entry);
}

namespace {

std::shared_ptr<const Code> generate_code(const ProgramImpl& p, std::string* why_not) {
    const auto t0 = std::chrono::steady_clock::now();
    if (!enabled()) {
        *why_not = "the compiled tier is off (TILEVK_JIT=0)";
        return nullptr;
    }
    if (!host_supported()) {
        *why_not = "the CPU lacks AVX2 or FMA";
        return nullptr;
    }
    const Analysis an = analyze(p);
    if (an.unknown_at >= 0) {
        const Inst& in = p.code[size_t(an.unknown_at)];
        *why_not = "IR op " + op_name(in.op) + (lowering(in) != op_info(in.op).lowering ? " (64-bit)" : "") + " at " +
                   std::to_string(an.unknown_at) + " is not compiled";
        return nullptr;
    }
    auto code = std::make_shared<Code>();
    CodeHolder holder;
    ErrorCollector errors;
    holder.init(runtime().environment());
    holder.setErrorHandler(&errors);
    StringLogger logger;
    const bool dump = std::getenv("TILEVK_JIT_DUMP") != nullptr;
    if (dump) holder.setLogger(&logger);
    x86::Assembler assembler(&holder);
    Generator gen(p, an, assembler, *code);
    if (!gen.generate(why_not)) return nullptr;
    Entry entry = nullptr;
    if (errors.error == kErrorOk) runtime().add(&entry, &holder);
    if (errors.error != kErrorOk || !entry) {
        *why_not = "code generation failed: " + (errors.message.empty() ? std::string("no code") : errors.message);
        return nullptr;
    }
    code->entry = entry;
    code->code_bytes = holder.codeSize();
    code->compile_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    if (dump) std::fprintf(stderr, "%s\n", logger.data());
    return code;
}

}  // namespace

namespace {

// ": 2 Sample, 1 LoadBuf" for the log line: which ops still leave the compiled code, the next ones to lower.
std::string helper_summary(const ProgramImpl& p) {
    std::map<std::string, int> count;
    for (const Inst& in : p.code)
        if (lowering(in) == Lowering::Helper) ++count[op_name(in.op)];
    std::string s;
    for (const auto& [name, n] : count) s += (s.empty() ? ": " : ", ") + std::to_string(n) + " " + name;
    return s;
}

}  // namespace

std::shared_ptr<const Code> compile(const ProgramImpl& p, std::string* why_not) {
    std::shared_ptr<const Code> code = generate_code(p, why_not);
    if (log_enabled()) {
        const char* stage = p.stage == Stage::Vertex ? "vertex" : p.stage == Stage::Fragment ? "fragment" : "compute";
        if (code)
            std::fprintf(stderr,
                         "tilevk: %s program compiled: %zu IR ops (%u native, %u through the interpreter%s), %zu "
                         "bytes of code in %.3f ms\n",
                         stage, p.code.size(), code->native_ops, code->helper_ops, helper_summary(p).c_str(),
                         code->code_bytes, code->compile_ms);
        else
            std::fprintf(stderr, "tilevk: %s program stays in the interpreter: %s\n", stage, why_not->c_str());
    }
    return code;
}

size_t run(const Code& code, Scratch::Impl& s, size_t pc) {
    static_assert(sizeof(std::atomic<bool>) == 1 && std::atomic<bool>::is_always_lock_free,
                  "the generated code reads the stop flag as one byte");
    // back_edges continues the count of the run's earlier phases (exec.cpp's watchdog counts over all of them)
    Frame f{s.regs.data(), s.local.data(), s.slots.data(), &s, s.stop, s.back_edges, s.shared, pc};
    const size_t next = code.entry(&f);
    s.back_edges = f.back_edges;
    return next;
}

std::string op_name(Op op) {
    switch (op) {  // the pointer and 64-bit ops, which this tier does not compile (analysis.cpp has no row for them)
        case Op::LoadPtr:
            return "LoadPtr";
        case Op::StorePtr:
            return "StorePtr";
        case Op::AtomicPtr:
            return "AtomicPtr";
        case Op::Wide:  // 64-bit integers and doubles (shader/README.md "64-bit types")
            return "Wide";
        case Op::LoadBufN:  // 8- and 16-bit buffer access and float16 conversions (shader/README.md)
            return "LoadBufN";
        case Op::StoreBufN:
            return "StoreBufN";
        case Op::HalfToFloat:
            return "HalfToFloat";
        case Op::FloatToHalf:
            return "FloatToHalf";
        default:
            break;
    }
    const OpInfo info = op_info(op);
    return info.name ? info.name : "op #" + std::to_string(unsigned(op));
}

}  // namespace tilevk::shader::jit
