// `drop-pass-depths`, for the targets whose printers print the IR as it
// stands (the macro programs): each pass.begin goes. Their passes are a
// loop the controller runs, whose comment could not say the depth; a pass
// the optimiser wrote out (an unrolled loop's trip, its depth a number)
// keeps its comment, `pass at depth D`, as a pass the lowering wrote out.
#include "cncc/ir/passes.h"

#include "rewriter.h"

#include "cncc/ir/sweep_pass.h"

namespace cncc::ir {

namespace {

class PassDepthDropper : public passes::Rewriter {
public:
  using Rewriter::Rewriter;

private:
  void visit(const Instruction& instruction) override {
    if (instruction.opcode != Opcode::PassBegin) {
      copy(instruction);
      return;
    }
    markChanged();
    if (std::optional<double> z = passes::constantValue(source_, instruction.operands[0])) {
      Instruction comment = instruction;
      comment.text = passDepthComment(*z);
      emitAs(comment, Opcode::Comment, {});
    }
  }
};

} // namespace

bool dropPassDepths(Function& function) {
  PassDepthDropper pass(function);
  function = pass.run();
  return pass.changed();
}

} // namespace cncc::ir
