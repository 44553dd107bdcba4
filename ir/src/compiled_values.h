// A value at the values the program was compiled with, for the
// legalisations that measure a lap's curve from its regions: a parameter at
// its default, pure arithmetic on such values folded as the interpreter
// computes it; nullopt for anything else (a loop's variable, an effect),
// unless told its value (a loop's variable in the trip the interpreter runs).
#pragma once

#include "cncc/ir/ir.h"

#include "passes/evaluate.h"
#include "passes/rewriter.h"

#include <map>
#include <optional>
#include <vector>

namespace cncc::ir {

class CompiledValues {
public:
  explicit CompiledValues(const Function& function) : function_(function) {}

  // `value` is `number` (told before anything that reads it is asked).
  void know(ValueId value, double number) { known_[value.index] = number; }

  std::optional<double> operator()(ValueId value) {
    std::vector<ValueId> work{value};
    while (!work.empty()) {
      ValueId next = work.back();
      if (known_.contains(next.index)) {
        work.pop_back();
        continue;
      }
      const Instruction& definition = function_.definition(next);
      if (std::optional<double> number = passes::constantValue(function_, next)) {
        known_[next.index] = number;
        continue;
      }
      if (definition.opcode == Opcode::Param) {
        known_[next.index] = function_.parameters[definition.index].defaultValue;
        continue;
      }
      if (!isPure(definition.opcode) || definition.opcode == Opcode::Loop) {
        known_[next.index] = std::nullopt;
        continue;
      }
      if (definition.opcode == Opcode::Select) {
        // The branch the condition chooses: the other may read what is not
        // known (a loop's variable) or fail at these values.
        if (std::optional<ValueId> chosen = chosenBranch(next, definition, work)) {
          auto found = known_.find(chosen->index);
          if (found == known_.end()) {
            work.push_back(*chosen);
          } else {
            known_[next.index] = found->second;
          }
        }
        continue;
      }
      std::vector<double> operands;
      bool ready = true;
      for (ValueId operand : definition.operands) {
        auto found = known_.find(operand.index);
        if (found == known_.end()) {
          work.push_back(operand);
          ready = false;
        } else if (found->second) {
          operands.push_back(*found->second);
        } else {
          known_[next.index] = std::nullopt; // reads what is not known
          ready = false;
          break;
        }
      }
      if (ready) {
        known_[next.index] = passes::evaluate(function_, definition, operands);
      }
    }
    return known_[value.index];
  }

private:
  // The operand a select's known condition chooses; nullopt while the
  // condition waits on the work list, or when it is not known (the select
  // is then not known either).
  std::optional<ValueId> chosenBranch(ValueId select, const Instruction& definition,
                                      std::vector<ValueId>& work) {
    ValueId condition = definition.operands[0];
    auto found = known_.find(condition.index);
    if (found == known_.end()) {
      work.push_back(condition);
      return std::nullopt;
    }
    if (!found->second) {
      known_[select.index] = std::nullopt;
      return std::nullopt;
    }
    return *found->second != 0 ? definition.operands[1] : definition.operands[2];
  }

  const Function& function_;
  std::map<std::uint32_t, std::optional<double>> known_;
};

} // namespace cncc::ir
