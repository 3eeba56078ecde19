// The other candidate code generator, measured against asmjit (shader/jit/README.md "Choosing the code
// generator"): the same IR, the same analysis (regions, region-local registers, constants) and the same memory
// model lowered to LLVM IR (<16 x i32> / <16 x float> values, no fast-math flags) and compiled by LLVM 15's ORC
// LLJIT for the host CPU. Covers the ops of bench_shaders.h; anything else reports itself unsupported.
#include "bench/shader/llvm_probe.h"

#include <llvm/ExecutionEngine/Orc/LLJIT.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/Intrinsics.h>
#include <llvm/IR/LegacyPassManager.h>
#include <llvm/IR/Verifier.h>
#include <llvm/Passes/PassBuilder.h>
#include <llvm/Support/TargetSelect.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <map>

#include "shader/jit/analysis.h"
#include "shader/jit/helpers.h"
#include "shader/jit/jit.h"

namespace tilevk::bench_probe {

using namespace tilevk::shader;
using namespace llvm;

namespace {

struct Lowering {
    const ProgramImpl& p;
    const jit::Analysis& an;
    LLVMContext& ctx;
    Module& mod;
    IRBuilder<> b;
    Function* fn = nullptr;
    Value *frame = nullptr, *regs = nullptr, *local = nullptr, *slots = nullptr;
    FixedVectorType *vi, *vf;
    std::map<uint32_t, Value*> cache;  // register -> value valid in the current region
    std::map<uint32_t, Value*> words;  // local word -> value
    std::vector<BasicBlock*> labels;
    BasicBlock* limit = nullptr;
    std::string unsupported;

    Lowering(const ProgramImpl& prog, const jit::Analysis& a, LLVMContext& c, Module& m)
        : p(prog), an(a), ctx(c), mod(m), b(c) {
        vi = FixedVectorType::get(Type::getInt32Ty(ctx), kLanes);
        vf = FixedVectorType::get(Type::getFloatTy(ctx), kLanes);
    }
    Value* at(Value* base, uint64_t bytes) { return b.CreateConstGEP1_64(b.getInt8Ty(), base, bytes); }
    Value* get(uint32_t r) {
        if (an.is_const[r])
            return ConstantVector::getSplat(ElementCount::getFixed(kLanes), b.getInt32(an.const_value[r]));
        auto it = cache.find(r);
        if (it != cache.end()) return it->second;
        Value* v = b.CreateAlignedLoad(vi, at(regs, uint64_t(r) * 64), Align(4));
        cache[r] = v;
        return v;
    }
    Value* getf(uint32_t r) { return b.CreateBitCast(get(r), vf); }
    void set(uint32_t r, Value* v) {
        if (v->getType() != vi) v = b.CreateBitCast(v, vi);
        if (!an.local[r]) b.CreateAlignedStore(v, at(regs, uint64_t(r) * 64), Align(4));
        cache[r] = v;
    }
    Value* word(uint32_t w) {
        auto it = words.find(w);
        if (it != words.end()) return it->second;
        Value* v = b.CreateAlignedLoad(vi, at(local, uint64_t(w) * 64), Align(4));
        words[w] = v;
        return v;
    }
    Value* splat(uint32_t x) { return ConstantVector::getSplat(ElementCount::getFixed(kLanes), b.getInt32(x)); }
    Value* any(Value* v) {
        Value* z = b.CreateICmpNE(v, splat(0));
        return b.CreateOrReduce(z);
    }
    Value* fminmax(Value* a, Value* c, bool min) {
        Value* cmp = min ? b.CreateFCmpOLT(a, c) : b.CreateFCmpOGT(a, c);
        Value* m = b.CreateOr(cmp, b.CreateFCmpUNO(c, c));
        return b.CreateSelect(m, a, c);
    }
    Value* unary_intrinsic(Intrinsic::ID id, Value* x) {
        return b.CreateCall(Intrinsic::getDeclaration(&mod, id, {vf}), {x});
    }
    void helper(const Inst* code) {
        auto* fty = FunctionType::get(b.getVoidTy(), {b.getPtrTy(), b.getPtrTy()}, false);
        Value* callee =
            b.CreateIntToPtr(b.getInt64(reinterpret_cast<uint64_t>(&jit::run_one_instruction)), b.getPtrTy());
        Value* scratch = b.CreateAlignedLoad(b.getPtrTy(), at(frame, offsetof(jit::Frame, scratch)), Align(8));
        b.CreateCall(fty, callee,
                     {scratch, b.CreateIntToPtr(b.getInt64(reinterpret_cast<uint64_t>(code)), b.getPtrTy())});
        for (auto it = cache.begin(); it != cache.end();) it = an.local[it->first] ? std::next(it) : cache.erase(it);
        if (code->op == Op::StoreLocal) words.clear();
    }
    void new_block() {
        BasicBlock* next = BasicBlock::Create(ctx, "", fn);
        b.SetInsertPoint(next);
    }
    bool emit(const Inst& in, const Inst* helper_code);
    bool lower(jit::Code& out);
};

// One switch over the interpreter's ops (over 150 lines): a case per op with its LLVM IR builder calls (a
// benchmark probe that measures LLVM as a code generator, kept as one readable table).
bool Lowering::emit(const Inst& in, const Inst* helper_code) {
    switch (in.op) {
        case Op::Mov:
            set(in.d, get(in.a));
            return true;
        case Op::Select:
        case Op::MaskedMov: {
            Value* c = get(in.c);
            Value* other = in.op == Op::Select ? get(in.b) : get(in.d);
            set(in.d, b.CreateOr(b.CreateAnd(c, get(in.a)), b.CreateAnd(b.CreateNot(c), other)));
            return true;
        }
        case Op::FAdd:  // LLVM does not promise which NaN a commutative operation returns: no attempt here
            set(in.d, b.CreateFAdd(getf(in.a), getf(in.b)));
            return true;
        case Op::FMul:
            set(in.d, b.CreateFMul(getf(in.a), getf(in.b)));
            return true;
        case Op::FSub:
            set(in.d, b.CreateFSub(getf(in.a), getf(in.b)));
            return true;
        case Op::FDiv:
            set(in.d, b.CreateFDiv(getf(in.a), getf(in.b)));
            return true;
        case Op::FNeg:
            set(in.d, b.CreateXor(get(in.a), splat(0x80000000u)));
            return true;
        case Op::FAbs:
            set(in.d, b.CreateAnd(get(in.a), splat(0x7fffffffu)));
            return true;
        case Op::FMin:
        case Op::FMax:
            set(in.d, fminmax(getf(in.a), getf(in.b), in.op == Op::FMin));
            return true;
        case Op::FOrdLt:
            set(in.d, b.CreateSExt(b.CreateFCmpOLT(getf(in.a), getf(in.b)), vi));
            return true;
        case Op::FOrdLe:
            set(in.d, b.CreateSExt(b.CreateFCmpOLE(getf(in.a), getf(in.b)), vi));
            return true;
        case Op::FOrdEq:
            set(in.d, b.CreateSExt(b.CreateFCmpOEQ(getf(in.a), getf(in.b)), vi));
            return true;
        case Op::IAdd:
            set(in.d, b.CreateAdd(get(in.a), get(in.b)));
            return true;
        case Op::ISub:
            set(in.d, b.CreateSub(get(in.a), get(in.b)));
            return true;
        case Op::And:
            set(in.d, b.CreateAnd(get(in.a), get(in.b)));
            return true;
        case Op::Or:
            set(in.d, b.CreateOr(get(in.a), get(in.b)));
            return true;
        case Op::Not:
            set(in.d, b.CreateNot(get(in.a)));
            return true;
        case Op::SLt:
            set(in.d, b.CreateSExt(b.CreateICmpSLT(get(in.a), get(in.b)), vi));
            return true;
        case Op::IEq:
            set(in.d, b.CreateSExt(b.CreateICmpEQ(get(in.a), get(in.b)), vi));
            return true;
        case Op::S2F:
            set(in.d, b.CreateSIToFP(get(in.a), vf));
            return true;
        case Op::Floor:
            set(in.d, unary_intrinsic(Intrinsic::floor, getf(in.a)));
            return true;
        case Op::Fract: {
            Value* a = getf(in.a);
            set(in.d, b.CreateFSub(a, unary_intrinsic(Intrinsic::floor, a)));
            return true;
        }
        case Op::Sqrt:
            set(in.d, unary_intrinsic(Intrinsic::sqrt, getf(in.a)));
            return true;
        case Op::InvSqrt:
            set(in.d, b.CreateFDiv(ConstantVector::getSplat(ElementCount::getFixed(kLanes),
                                                            ConstantFP::get(b.getFloatTy(), 1.0)),
                                   unary_intrinsic(Intrinsic::sqrt, getf(in.a))));
            return true;
        case Op::LoadLocalFixed:
            set(in.d, word(in.imm));
            return true;
        case Op::StoreLocalFixed: {
            Value* c = get(in.c);
            Value* v = b.CreateOr(b.CreateAnd(c, get(in.b)), b.CreateAnd(b.CreateNot(c), word(in.imm)));
            b.CreateAlignedStore(v, at(local, uint64_t(in.imm) * 64), Align(4));
            words[in.imm] = v;
            return true;
        }
        case Op::LoadBufUniform: {
            if (in.imm >= p.num_slots) {
                set(in.d, splat(0));
                return true;
            }
            // desc && desc->buffer.data && extra + 4 <= size ? load : 0, as exec.cpp
            Value* desc = b.CreateAlignedLoad(b.getPtrTy(), at(slots, uint64_t(in.imm) * 8), Align(8));
            BasicBlock* from = b.GetInsertBlock();
            BasicBlock* check = BasicBlock::Create(ctx, "", fn);
            BasicBlock* read = BasicBlock::Create(ctx, "", fn);
            BasicBlock* done = BasicBlock::Create(ctx, "", fn);
            b.CreateCondBr(b.CreateIsNull(desc), done, check);
            b.SetInsertPoint(check);
            Value* data = b.CreateAlignedLoad(
                b.getPtrTy(), at(desc, offsetof(Descriptor, buffer) + offsetof(BufferView, data)), Align(8));
            Value* size = b.CreateAlignedLoad(
                b.getInt64Ty(), at(desc, offsetof(Descriptor, buffer) + offsetof(BufferView, size)), Align(8));
            Value* ok = b.CreateAnd(b.CreateIsNotNull(data), b.CreateICmpULE(b.getInt64(uint64_t(in.extra) + 4), size));
            b.CreateCondBr(ok, read, done);
            b.SetInsertPoint(read);
            Value* v = b.CreateAlignedLoad(b.getInt32Ty(), at(data, in.extra), Align(1));
            b.CreateBr(done);
            b.SetInsertPoint(done);
            PHINode* phi = b.CreatePHI(b.getInt32Ty(), 3);
            phi->addIncoming(b.getInt32(0), from);
            phi->addIncoming(b.getInt32(0), check);
            phi->addIncoming(v, read);
            set(in.d, b.CreateVectorSplat(kLanes, phi));
            return true;
        }
        case Op::JumpIfNone: {
            BasicBlock* next = BasicBlock::Create(ctx, "", fn);
            b.CreateCondBr(any(get(in.a)), next, labels[in.imm]);
            b.SetInsertPoint(next);
            return true;
        }
        case Op::JumpIfAny: {
            BasicBlock* take = BasicBlock::Create(ctx, "", fn);
            BasicBlock* stay = BasicBlock::Create(ctx, "", fn);
            b.CreateCondBr(any(get(in.a)), take, stay);
            b.SetInsertPoint(take);
            Value* ep = at(frame, offsetof(jit::Frame, back_edges));
            Value* e = b.CreateAdd(b.CreateAlignedLoad(b.getInt64Ty(), ep, Align(8)), b.getInt64(1));
            b.CreateAlignedStore(e, ep, Align(8));
            b.CreateCondBr(b.CreateICmpUGT(e, b.getInt64(kMaxLoopBackEdges)), limit, labels[in.imm]);
            b.SetInsertPoint(stay);
            return true;
        }
        case Op::Kill:
            set(in.d, b.CreateAnd(b.CreateNot(get(in.a)), get(in.d)));
            return true;
        case Op::Halt:
            b.CreateRetVoid();
            new_block();
            return true;
        default:
            if (jit::lowering(in) != jit::Lowering::Helper) {
                unsupported = jit::op_name(in.op);
                return false;
            }
            helper(helper_code);
            return true;
    }
}

bool Lowering::lower(jit::Code& out) {
    auto* fty = FunctionType::get(b.getVoidTy(), {b.getPtrTy()}, false);
    fn = Function::Create(fty, Function::ExternalLinkage, "shader", mod);
    BasicBlock* entry = BasicBlock::Create(ctx, "entry", fn);
    b.SetInsertPoint(entry);
    frame = fn->getArg(0);
    regs = b.CreateAlignedLoad(b.getPtrTy(), at(frame, offsetof(jit::Frame, regs)), Align(8));
    local = b.CreateAlignedLoad(b.getPtrTy(), at(frame, offsetof(jit::Frame, local)), Align(8));
    slots = b.CreateAlignedLoad(b.getPtrTy(), at(frame, offsetof(jit::Frame, slots)), Align(8));
    const size_t n = p.code.size();
    labels.assign(n + 1, nullptr);
    for (size_t i = 0; i <= n; ++i)
        if (an.label[i]) labels[i] = BasicBlock::Create(ctx, "", fn);
    limit = BasicBlock::Create(ctx, "limit", fn);
    size_t helpers = 0;
    for (const Inst& in : p.code) helpers += jit::lowering(in) == jit::Lowering::Helper;
    out.helper_code = std::make_unique<Inst[]>(std::max<size_t>(1, 2 * helpers));
    size_t used = 0;
    for (size_t pc = 0; pc < n; ++pc) {
        if (an.label[pc]) {
            b.CreateBr(labels[pc]);
            b.SetInsertPoint(labels[pc]);
            cache.clear(), words.clear();
        }
        const Inst& in = p.code[pc];
        Inst* code = nullptr;
        if (jit::lowering(in) == jit::Lowering::Helper) {
            code = out.helper_code.get() + 2 * used++;
            code[0] = in, code[1] = Inst{Op::Halt};
        }
        if (!emit(in, code)) return false;
    }
    if (labels[n]) {
        b.CreateBr(labels[n]);
        b.SetInsertPoint(labels[n]);
    }
    b.CreateRetVoid();
    b.SetInsertPoint(limit);
    auto* hty = FunctionType::get(b.getVoidTy(), {b.getPtrTy()}, false);
    Value* callee = b.CreateIntToPtr(b.getInt64(reinterpret_cast<uint64_t>(&jit::count_loop_limit_hit)), b.getPtrTy());
    b.CreateCall(hty, callee, {b.CreateAlignedLoad(b.getPtrTy(), at(frame, offsetof(jit::Frame, scratch)), Align(8))});
    b.CreateRetVoid();
    return !verifyFunction(*fn, &errs());
}

orc::LLJIT& engine() {
    static std::unique_ptr<orc::LLJIT> jit = [] {
        InitializeNativeTarget();
        InitializeNativeTargetAsmPrinter();
        return cantFail(orc::LLJITBuilder().create());
    }();
    return *jit;
}

}  // namespace

double llvm_init_ms() {
    const auto t0 = std::chrono::steady_clock::now();
    engine();
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::shared_ptr<jit::Code> llvm_compile(const ProgramImpl& p, int opt_level, std::string* why) {
    static std::atomic<int> serial{0};
    const jit::Analysis an = jit::analyze(p);
    auto ctx = std::make_unique<LLVMContext>();
    auto mod = std::make_unique<Module>("shader" + std::to_string(++serial), *ctx);
    mod->setDataLayout(engine().getDataLayout());
    // LLVM owns the code: the deleter keeps jit::Code from handing it to asmjit's runtime
    std::shared_ptr<jit::Code> code(new jit::Code, [](jit::Code* c) {
        c->entry = nullptr;
        delete c;
    });
    Lowering low(p, an, *ctx, *mod);
    if (!low.lower(*code)) {
        *why = "unsupported " + low.unsupported;
        return nullptr;
    }
    Function* fn = low.fn;
    fn->setName("shader" + std::to_string(serial.load()));
    std::string name = fn->getName().str();
    {
        LoopAnalysisManager lam;
        FunctionAnalysisManager fam;
        CGSCCAnalysisManager cgam;
        ModuleAnalysisManager mam;
        PassBuilder pb;
        pb.registerModuleAnalyses(mam);
        pb.registerCGSCCAnalyses(cgam);
        pb.registerFunctionAnalyses(fam);
        pb.registerLoopAnalyses(lam);
        pb.crossRegisterProxies(lam, fam, cgam, mam);
        OptimizationLevel level = opt_level >= 2 ? OptimizationLevel::O2 : OptimizationLevel::O1;
        ModulePassManager mpm = pb.buildPerModuleDefaultPipeline(level);
        mpm.run(*mod, mam);
    }
    cantFail(engine().addIRModule(orc::ThreadSafeModule(std::move(mod), std::move(ctx))));
    auto sym = engine().lookup(name);
    if (!sym) {
        *why = toString(sym.takeError());
        return nullptr;
    }
    code->entry = sym->toPtr<jit::Entry>();
    return code;
}

}  // namespace tilevk::bench_probe
