// `drop-pass-depths`, for the targets whose printers print the IR as it
// stands (the macro programs): each pass.begin goes. Their passes are a
// loop the controller runs, whose comment could not say the depth (and a
// loop the optimiser wrote out says none either, as the loop it was).
#include "cncc/ir/passes.h"

#include "rewriter.h"

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
  }
};

} // namespace

bool dropPassDepths(Function& function) {
  PassDepthDropper pass(function);
  function = pass.run();
  return pass.changed();
}

} // namespace cncc::ir
