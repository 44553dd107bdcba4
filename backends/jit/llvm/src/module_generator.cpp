#include "module_generator.h"

#include "jit_runtime.h"

#include "cncc/backends/jit_compiler.h"

#include "cncc/geom/math_functions.h"
#include "cncc/ir/arithmetic.h"

#include <llvm/IR/Constants.h>
#include <llvm/IR/Function.h>
#include <llvm/IR/IRBuilder.h>
#include <llvm/IR/Intrinsics.h>
#include <llvm/IR/LLVMContext.h>
#include <llvm/IR/Module.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

namespace cncc::backends::jit {

namespace {

using ir::Opcode;

// Whether the interpreter may stop at this instruction (an error) or enter a
// region there: the step count must be exact up to it.
bool endsStepSegment(Opcode opcode) {
  return opcode == Opcode::TableLoad || opcode == Opcode::Loop || opcode == Opcode::If;
}

// The C library function the interpreter computes an operation by (the one
// table of math functions, cncc/geom/math_functions.h).
std::string libmFunction(Opcode opcode) {
  std::optional<geom::MathFunction> function = ir::mathFunctionOf(opcode);
  return function ? std::string(geom::mathFunctionInfo(*function).cFunction) : std::string();
}

class ModuleGenerator {
public:
  ModuleGenerator(const ir::Function& function, llvm::LLVMContext& context)
      : function_(function), context_(context),
        module_(std::make_unique<llvm::Module>(function.name, context)), builder_(context),
        f64_(builder_.getDoubleTy()), i32_(builder_.getInt32Ty()), i64_(builder_.getInt64Ty()),
        values_(function.valueTypes.size(), nullptr) {}

  GeneratedModule generate() {
    createEntry();
    createTables();
    loadParameters();
    emitRegion(function_.body);
    builder_.CreateRet(builder_.getInt32(0));
    return {std::move(module_), std::move(comments_)};
  }

private:
  void createEntry() {
    llvm::Type* opaque = builder_.getInt8PtrTy();
    auto* type = llvm::FunctionType::get(
        i32_,
        {llvm::PointerType::getUnqual(f64_), opaque, i64_, llvm::PointerType::getUnqual(i64_)},
        false);
    entry_ =
        llvm::Function::Create(type, llvm::Function::ExternalLinkage,
                               llvm::StringRef(entryName.data(), entryName.size()), module_.get());
    entry_->addFnAttr(llvm::Attribute::NoUnwind);
    // The parameters are read only, and by nothing the code calls.
    entry_->addParamAttr(0, llvm::Attribute::NoAlias);
    entry_->addParamAttr(0, llvm::Attribute::ReadOnly);
    parameters_ = entry_->getArg(0);
    runContext_ = entry_->getArg(1);
    maximumSteps_ = entry_->getArg(2);
    steps_ = entry_->getArg(3);

    auto* start = llvm::BasicBlock::Create(context_, "start", entry_);
    failure_ = llvm::BasicBlock::Create(context_, "failure", entry_);
    builder_.SetInsertPoint(failure_);
    builder_.CreateRet(builder_.getInt32(1));
    builder_.SetInsertPoint(start);
  }

  void createTables() {
    for (const std::vector<double>& table : function_.tables) {
      llvm::Constant* data = llvm::ConstantDataArray::get(context_, llvm::ArrayRef<double>(table));
      auto* global = new llvm::GlobalVariable(*module_, data->getType(), true,
                                              llvm::GlobalValue::PrivateLinkage, data, "table");
      global->setUnnamedAddr(llvm::GlobalValue::UnnamedAddr::Global);
      tables_.push_back(global);
    }
  }

  // Loaded once at the start: a parameter does not change during a run.
  void loadParameters() {
    for (std::size_t index = 0; index < function_.parameters.size(); ++index) {
      llvm::Value* address = builder_.CreateConstInBoundsGEP1_64(f64_, parameters_, index);
      parameterValues_.push_back(
          builder_.CreateLoad(f64_, address, function_.parameters[index].name));
    }
  }

  // The interpreter counts one step per instruction before running it. The
  // count is added a segment at a time, a segment ending where the
  // interpreter could stop with another error or enter a region.
  void emitRegion(const ir::Region& region) {
    const std::vector<ir::InstructionId>& ids = region.instructions;
    for (std::size_t position = 0; position < ids.size();) {
      std::size_t end = position;
      while (end < ids.size() && !endsStepSegment(function_.instructions[ids[end]].opcode)) {
        ++end;
      }
      end = std::min(end + 1, ids.size());
      emitStepCount(end - position);
      for (; position < end; ++position) {
        emitInstruction(function_.instructions[ids[position]]);
      }
    }
  }

  void emitStepCount(std::size_t count) {
    llvm::Value* steps =
        builder_.CreateAdd(builder_.CreateLoad(i64_, steps_), builder_.getInt64(count));
    builder_.CreateStore(steps, steps_);
    llvm::Value* withinLimit = builder_.CreateICmpULE(steps, maximumSteps_);
    failUnless(withinLimit, "cncc_jit_step_limit_error", {i64_}, {maximumSteps_});
  }

  void emitInstruction(const ir::Instruction& instruction) {
    const std::vector<ir::ValueId>& operands = instruction.operands;
    llvm::Value* result = nullptr;
    switch (instruction.opcode) {
    case Opcode::Const:
    case Opcode::ConstBool:
      result = llvm::ConstantFP::get(f64_, instruction.number);
      break;
    case Opcode::Param:
      result = parameterValues_[instruction.index];
      break;
    case Opcode::TableLoad:
      result = emitTableLoad(instruction);
      break;
    case Opcode::Add:
    case Opcode::Sub:
    case Opcode::Mul:
    case Opcode::Div:
    case Opcode::Min:
    case Opcode::Max:
      result = emitArithmetic(instruction.opcode, value(operands[0]), value(operands[1]));
      break;
    case Opcode::Rem:
    case Opcode::Pow:
    case Opcode::Atan2:
      result = callLibm(instruction.opcode, {value(operands[0]), value(operands[1])});
      break;
    case Opcode::Neg:
      result = builder_.CreateFNeg(value(operands[0]));
      break;
    case Opcode::Abs:
    case Opcode::Sqrt:
    case Opcode::Floor:
    case Opcode::Ceil:
    case Opcode::Round:
      result = emitExactUnary(instruction.opcode, value(operands[0]));
      break;
    case Opcode::Sin:
    case Opcode::Cos:
    case Opcode::Tan:
    case Opcode::Asin:
    case Opcode::Acos:
    case Opcode::Atan:
    case Opcode::Exp:
    case Opcode::Ln:
      result = callLibm(instruction.opcode, {value(operands[0])});
      break;
    case Opcode::Select:
      result =
          builder_.CreateSelect(truth(value(operands[0])), value(operands[1]), value(operands[2]));
      break;
    case Opcode::Lt:
    case Opcode::Le:
    case Opcode::Gt:
    case Opcode::Ge:
    case Opcode::Eq:
    case Opcode::Ne:
    case Opcode::And:
    case Opcode::Or:
      result = asNumber(emitCondition(instruction.opcode, value(operands[0]), value(operands[1])));
      break;
    case Opcode::Not:
      result = asNumber(builder_.CreateNot(truth(value(operands[0]))));
      break;
    case Opcode::Loop:
      emitLoop(instruction);
      return;
    case Opcode::LoopNext: // read by its loop (emitLoop)
      return;
    case Opcode::If:
      emitIf(instruction);
      return;
    case Opcode::CurveLap:
    case Opcode::CurvePoint:
    case Opcode::CurveArc:
    case Opcode::CurveWalk:
      throw backends::JitError(
          "a curve.lap must be expanded (expand-curve-laps) before the JIT compiles it");
    case Opcode::Rapid:
    case Opcode::Climb:
    case Opcode::Feed:
    case Opcode::Arc:
    case Opcode::Nurbs:
    case Opcode::Spline:
    case Opcode::Polynomial:
    case Opcode::Alarm:
    case Opcode::Spindle:
    case Opcode::Tool:
    case Opcode::Origin:
    case Opcode::Coolant:
    case Opcode::Contouring:
    case Opcode::Home:
    case Opcode::Compensation:
    case Opcode::Comment:
    case Opcode::PassBegin:
    case Opcode::CutBegin:
    case Opcode::CornerArc:
      emitEffect(instruction);
      return;
    }
    values_[instruction.result.index] = result;
  }

  llvm::Value* value(ir::ValueId id) const { return values_[id.index]; }

  // The interpreter's `a != 0`: true for NaN too.
  llvm::Value* truth(llvm::Value* number) {
    return builder_.CreateFCmpUNE(number, llvm::ConstantFP::get(f64_, 0.0));
  }

  llvm::Value* asNumber(llvm::Value* condition) {
    return builder_.CreateSelect(condition, llvm::ConstantFP::get(f64_, 1.0),
                                 llvm::ConstantFP::get(f64_, 0.0));
  }

  llvm::Value* emitArithmetic(Opcode opcode, llvm::Value* a, llvm::Value* b) {
    switch (opcode) {
    case Opcode::Add:
      return builder_.CreateFAdd(a, b);
    case Opcode::Sub:
      return builder_.CreateFSub(a, b);
    case Opcode::Mul:
      return builder_.CreateFMul(a, b);
    case Opcode::Div:
      return builder_.CreateFDiv(a, b);
    case Opcode::Min: // std::min(a, b): b < a ? b : a
      return builder_.CreateSelect(builder_.CreateFCmpOLT(b, a), b, a);
    default: // Max, std::max(a, b): a < b ? b : a
      return builder_.CreateSelect(builder_.CreateFCmpOLT(a, b), b, a);
    }
  }

  // Operations whose result is exactly defined (no rounding choice), as
  // LLVM intrinsics: the same numbers as the C functions.
  llvm::Value* emitExactUnary(Opcode opcode, llvm::Value* a) {
    llvm::Intrinsic::ID intrinsic = llvm::Intrinsic::fabs;
    switch (opcode) {
    case Opcode::Sqrt:
      intrinsic = llvm::Intrinsic::sqrt;
      break;
    case Opcode::Floor:
      intrinsic = llvm::Intrinsic::floor;
      break;
    case Opcode::Ceil:
      intrinsic = llvm::Intrinsic::ceil;
      break;
    case Opcode::Round: // halves away from zero, as C's round
      intrinsic = llvm::Intrinsic::round;
      break;
    default:
      break;
    }
    return builder_.CreateUnaryIntrinsic(intrinsic, a);
  }

  llvm::Value* emitCondition(Opcode opcode, llvm::Value* a, llvm::Value* b) {
    switch (opcode) {
    case Opcode::Lt:
      return builder_.CreateFCmpOLT(a, b);
    case Opcode::Le:
      return builder_.CreateFCmpOLE(a, b);
    case Opcode::Gt:
      return builder_.CreateFCmpOGT(a, b);
    case Opcode::Ge:
      return builder_.CreateFCmpOGE(a, b);
    case Opcode::Eq:
      return builder_.CreateFCmpOEQ(a, b);
    case Opcode::Ne:
      return builder_.CreateFCmpUNE(a, b);
    case Opcode::And:
      return builder_.CreateAnd(truth(a), truth(b));
    default: // Or
      return builder_.CreateOr(truth(a), truth(b));
    }
  }

  // The C function itself, as the interpreter calls it. Declared without
  // side effects: the code never reads errno.
  llvm::Value* callLibm(Opcode opcode, std::vector<llvm::Value*> arguments) {
    std::vector<llvm::Type*> types(arguments.size(), f64_);
    llvm::FunctionCallee callee = module_->getOrInsertFunction(
        libmFunction(opcode), llvm::FunctionType::get(f64_, types, false));
    if (auto* declared = llvm::dyn_cast<llvm::Function>(callee.getCallee())) {
      declared->setDoesNotAccessMemory();
      declared->setDoesNotThrow();
      declared->setWillReturn();
    }
    return builder_.CreateCall(callee, arguments);
  }

  // index >= 0 && index < size, else the interpreter's error; then the
  // element at the index truncated to a whole number.
  llvm::Value* emitTableLoad(const ir::Instruction& instruction) {
    llvm::Value* index = value(instruction.operands[0]);
    llvm::GlobalVariable* table = tables_[instruction.index];
    std::uint64_t size = function_.tables[instruction.index].size();
    llvm::Value* inRange = builder_.CreateAnd(
        builder_.CreateFCmpOGE(index, llvm::ConstantFP::get(f64_, 0.0)),
        builder_.CreateFCmpOLT(index, llvm::ConstantFP::get(f64_, static_cast<double>(size))));
    failUnless(inRange, "cncc_jit_table_index_error", {f64_, i32_, i64_},
               {index, builder_.getInt32(instruction.index), builder_.getInt64(size)});
    llvm::Value* element = builder_.CreateInBoundsGEP(
        table->getValueType(), table, {builder_.getInt64(0), builder_.CreateFPToUI(index, i64_)});
    return builder_.CreateLoad(f64_, element);
  }

  llvm::Value* isFinite(llvm::Value* number) {
    llvm::Value* magnitude = builder_.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, number);
    return builder_.CreateFCmpONE(
        magnitude, llvm::ConstantFP::get(f64_, std::numeric_limits<double>::infinity()));
  }

  // for (double i = low; i <= high; ++i) body, as the interpreter runs it.
  void emitLoop(const ir::Instruction& loop) {
    llvm::Value* low = value(loop.operands[0]);
    llvm::Value* high = value(loop.operands[1]);
    failUnless(builder_.CreateAnd(isFinite(low), isFinite(high)), "cncc_jit_loop_bound_error", {},
               {});
    llvm::BasicBlock* before = builder_.GetInsertBlock();
    auto* header = llvm::BasicBlock::Create(context_, "loop", entry_);
    auto* body = llvm::BasicBlock::Create(context_, "loop.body", entry_);
    auto* after = llvm::BasicBlock::Create(context_, "loop.end", entry_);
    builder_.CreateBr(header);

    builder_.SetInsertPoint(header);
    llvm::PHINode* induction = builder_.CreatePHI(f64_, 2, "i");
    induction->addIncoming(low, before);
    ir::ValueId advance = ir::loopAdvance(function_, loop);
    builder_.CreateCondBr(advance.valid() ? builder_.CreateFCmpOLT(induction, high)
                                          : builder_.CreateFCmpOLE(induction, high),
                          body, after);

    builder_.SetInsertPoint(body);
    values_[loop.result.index] = induction;
    emitRegion(loop.regions[0]);
    llvm::Value* next = nullptr;
    if (advance.valid()) {
      // loop.next: the body's value, which must exceed the variable.
      next = value(advance);
      failUnless(builder_.CreateFCmpOGT(next, induction), "cncc_jit_loop_advance_error",
                 {f64_, f64_}, {next, induction});
    } else {
      next = builder_.CreateFAdd(induction, llvm::ConstantFP::get(f64_, 1.0));
    }
    induction->addIncoming(next, builder_.GetInsertBlock());
    builder_.CreateBr(header);

    builder_.SetInsertPoint(after);
  }

  void emitIf(const ir::Instruction& instruction) {
    auto* thenBlock = llvm::BasicBlock::Create(context_, "then", entry_);
    auto* elseBlock = llvm::BasicBlock::Create(context_, "else", entry_);
    auto* after = llvm::BasicBlock::Create(context_, "if.end", entry_);
    builder_.CreateCondBr(truth(value(instruction.operands[0])), thenBlock, elseBlock);
    builder_.SetInsertPoint(thenBlock);
    emitRegion(instruction.regions[0]);
    builder_.CreateBr(after);
    builder_.SetInsertPoint(elseBlock);
    emitRegion(instruction.regions[1]);
    builder_.CreateBr(after);
    builder_.SetInsertPoint(after);
  }

  void emitEffect(const ir::Instruction& instruction) {
    std::vector<llvm::Value*> arguments;
    for (ir::ValueId operand : instruction.operands) {
      arguments.push_back(value(operand));
    }
    const char* callback = "cncc_jit_rapid";
    switch (instruction.opcode) {
    case Opcode::Climb:
      callback = "cncc_jit_climb";
      break;
    case Opcode::Feed:
      callback = "cncc_jit_feed";
      break;
    case Opcode::Arc:
      callback = "cncc_jit_arc";
      arguments.insert(arguments.begin(),
                       llvm::ConstantFP::get(f64_, static_cast<double>(instruction.index)));
      break;
    case Opcode::Nurbs:
      // The weights one by one, then the move (its table by index).
      for (std::size_t k = 2; k < arguments.size(); ++k) {
        callRuntime("cncc_jit_nurbs_weight", {f64_}, {arguments[k]});
      }
      callback = "cncc_jit_nurbs";
      arguments = {builder_.getInt32(instruction.index), arguments[0], arguments[1]};
      break;
    case Opcode::Spline:
      callback = "cncc_jit_spline";
      arguments = {builder_.getInt32(instruction.index), arguments[0], arguments[1]};
      break;
    case Opcode::Polynomial:
      callback = "cncc_jit_polynomial";
      break;
    case Opcode::Spindle:
      callback = "cncc_jit_spindle";
      break;
    case Opcode::PassBegin:
      callback = "cncc_jit_pass_begin";
      break;
    case Opcode::CornerArc:
      callback = "cncc_jit_corner_arc";
      break;
    case Opcode::Tool:
      callback = "cncc_jit_tool";
      arguments = {llvm::ConstantFP::get(f64_, instruction.number), arguments[0],
                   builder_.getInt32(instruction.index)};
      break;
    case Opcode::Origin:
    case Opcode::Coolant:
    case Opcode::Contouring:
    case Opcode::Home:
    case Opcode::Compensation:
      callback = "cncc_jit_setting";
      arguments = {builder_.getInt32(static_cast<std::uint32_t>(instruction.opcode)),
                   llvm::ConstantFP::get(f64_, instruction.number),
                   builder_.getInt32(instruction.index)};
      break;
    case Opcode::Comment:
    case Opcode::Alarm:
      callback = instruction.opcode == Opcode::Comment ? "cncc_jit_comment" : "cncc_jit_alarm";
      arguments = {builder_.getInt32(static_cast<std::uint32_t>(comments_.size()))};
      comments_.push_back(instruction.text);
      break;
    case Opcode::CutBegin:
      callback = "cncc_jit_cut_begin";
      arguments = {builder_.getInt32(instruction.index)};
      break;
    default:
      break;
    }
    std::vector<llvm::Type*> types;
    for (llvm::Value* argument : arguments) {
      types.push_back(argument->getType());
    }
    llvm::Value* status = callRuntime(callback, types, arguments);
    // A failed callback has stored its exception in the run context.
    llvm::Value* recorded = builder_.CreateICmpEQ(status, builder_.getInt32(0));
    auto* next = llvm::BasicBlock::Create(context_, "recorded", entry_);
    builder_.CreateCondBr(recorded, next, failure_);
    builder_.SetInsertPoint(next);
  }

  // Calls a runtime callback: (RunContext*, arguments...) -> int32.
  llvm::Value* callRuntime(const char* name, std::vector<llvm::Type*> types,
                           std::vector<llvm::Value*> arguments) {
    types.insert(types.begin(), runContext_->getType());
    arguments.insert(arguments.begin(), runContext_);
    llvm::FunctionCallee callee =
        module_->getOrInsertFunction(name, llvm::FunctionType::get(i32_, types, false));
    if (auto* declared = llvm::dyn_cast<llvm::Function>(callee.getCallee())) {
      declared->setDoesNotThrow();
    }
    return builder_.CreateCall(callee, arguments);
  }

  // Continues where `condition` holds; otherwise records the error with the
  // named callback and returns the failure.
  void failUnless(llvm::Value* condition, const char* errorCallback, std::vector<llvm::Type*> types,
                  std::vector<llvm::Value*> arguments) {
    auto* error = llvm::BasicBlock::Create(context_, "error", entry_);
    auto* next = llvm::BasicBlock::Create(context_, "checked", entry_);
    builder_.CreateCondBr(condition, next, error);
    builder_.SetInsertPoint(error);
    llvm::Value* call = callRuntime(errorCallback, std::move(types), std::move(arguments));
    llvm::cast<llvm::CallInst>(call)->getCalledFunction()->addFnAttr(llvm::Attribute::Cold);
    builder_.CreateBr(failure_);
    builder_.SetInsertPoint(next);
  }

  const ir::Function& function_;
  llvm::LLVMContext& context_;
  std::unique_ptr<llvm::Module> module_;
  llvm::IRBuilder<> builder_;
  llvm::Type* f64_;
  llvm::IntegerType* i32_;
  llvm::IntegerType* i64_;

  llvm::Function* entry_ = nullptr;
  llvm::BasicBlock* failure_ = nullptr;
  llvm::Value* parameters_ = nullptr;
  llvm::Value* runContext_ = nullptr;
  llvm::Value* maximumSteps_ = nullptr;
  llvm::Value* steps_ = nullptr;

  std::vector<llvm::Value*> values_;
  std::vector<llvm::Value*> parameterValues_;
  std::vector<llvm::GlobalVariable*> tables_;
  std::vector<std::string> comments_;
};

} // namespace

GeneratedModule generateModule(const ir::Function& function, llvm::LLVMContext& context) {
  return ModuleGenerator(function, context).generate();
}

} // namespace cncc::backends::jit
