#include "cncc/ir/register_allocation.h"

#include "passes/rewriter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <set>
#include <tuple>

namespace cncc::ir {

int bracketedDepth(const InlineShape& shape) {
  return shape.form == InlineForm::Atom ? shape.bracketDepth : shape.bracketDepth + 1;
}

namespace {

InlineShape conservativeShape(const Function&, const Instruction&,
                              std::span<const InlineShape> operands) {
  InlineShape shape{1, InlineForm::Atom, 1};
  for (const InlineShape& operand : operands) {
    shape.bracketDepth = std::max(shape.bracketDepth, operand.bracketDepth + 1);
    shape.operations += operand.operations;
  }
  return shape;
}

// Where each instruction sits in the program, counted in steps of two so
// that an operation written as several statements can read its operands
// one step after its result is first written.
struct ProgramLayout {
  std::vector<int> position; // per instruction
  std::vector<std::vector<InstructionId>>
      loops;                            // per instruction: enclosing loops, outermost first
  std::map<InstructionId, int> loopEnd; // per loop: where its test and increment sit
  std::vector<InstructionId> order;     // every instruction, in program order
};

void layOutRegion(const Function& function, const Region& region,
                  std::vector<InstructionId>& enclosing, ProgramLayout& layout, int& next) {
  for (InstructionId id : region.instructions) {
    const Instruction& instruction = function.instructions[id];
    layout.position[id] = next;
    next += 2;
    layout.loops[id] = enclosing;
    layout.order.push_back(id);
    bool isLoop = instruction.opcode == Opcode::Loop;
    if (isLoop) {
      enclosing.push_back(id);
    }
    for (const Region& nested : instruction.regions) {
      layOutRegion(function, nested, enclosing, layout, next);
    }
    if (isLoop) {
      enclosing.pop_back();
      layout.loopEnd[id] = next;
      next += 2;
    }
  }
}

class Allocator {
public:
  Allocator(const Function& function, const AllocationOptions& options)
      : function_(function), options_(options) {
    if (!options_.shape) {
      options_.shape = conservativeShape;
    }
  }

  AllocationResult run() {
    std::size_t valueCount = function_.valueTypes.size();
    allocation_.variableOfValue.assign(valueCount, -1);
    materialized_.assign(valueCount, false);
    useCount_.assign(valueCount, 0);
    layOut();
    markNeeded();
    countUses();
    chooseMaterialized();
    fitExpressions();
    if (result_.failures.empty() && options_.stepScaledLoops) {
      stepScaledLoops();
    }
    if (result_.failures.empty()) {
      assignVariables();
      fitNumberedStatements();
    }
    result_.allocation = std::move(allocation_);
    return std::move(result_);
  }

private:
  const Instruction& definition(ValueId value) const { return function_.definition(value); }
  InstructionId definitionId(ValueId value) const { return function_.definitions[value.index]; }

  bool isStatementOpcode(Opcode opcode) const {
    const std::vector<Opcode>& list = options_.statementOpcodes;
    return std::find(list.begin(), list.end(), opcode) != list.end();
  }

  void layOut() {
    layout_.position.assign(function_.instructions.size(), -1);
    layout_.loops.assign(function_.instructions.size(), {});
    std::vector<InstructionId> enclosing;
    int next = 0;
    layOutRegion(function_, function_.body, enclosing, layout_, next);
  }

  // Effects and control flow are needed; so is everything they read.
  void markNeeded() {
    needed_.assign(function_.instructions.size(), false);
    std::vector<InstructionId> work;
    for (InstructionId id : layout_.order) {
      if (!isPure(function_.instructions[id].opcode)) {
        work.push_back(id);
      }
    }
    while (!work.empty()) {
      InstructionId id = work.back();
      work.pop_back();
      if (needed_[id]) {
        continue;
      }
      needed_[id] = true;
      for (ValueId operand : function_.instructions[id].operands) {
        work.push_back(definitionId(operand));
      }
    }
  }

  void countUses() {
    for (InstructionId id : layout_.order) {
      if (!needed_[id]) {
        continue;
      }
      const Instruction& instruction = function_.instructions[id];
      int weight = isStatementOpcode(instruction.opcode) ? 2 : 1;
      for (ValueId operand : instruction.operands) {
        useCount_[operand.index] += weight;
      }
    }
  }

  // Values that need a variable whatever the limits say.
  void chooseMaterialized() {
    for (InstructionId id : layout_.order) {
      const Instruction& instruction = function_.instructions[id];
      if (!needed_[id] || !instruction.result.valid()) {
        continue;
      }
      ValueId value = instruction.result;
      Opcode opcode = instruction.opcode;
      if (opcode == Opcode::Const || opcode == Opcode::ConstBool ||
          function_.valueTypes[value.index] != ValueType::F64) {
        continue;
      }
      if (opcode == Opcode::Loop || opcode == Opcode::Param || isStatementOpcode(opcode) ||
          useCount_[value.index] > 1) {
        materialized_[value.index] = true;
      }
    }
    // A value read inside a loop that does not define it is computed once.
    for (InstructionId id : layout_.order) {
      if (!needed_[id]) {
        continue;
      }
      for (ValueId operand : function_.instructions[id].operands) {
        if (!isConstant(operand) && function_.valueTypes[operand.index] == ValueType::F64 &&
            layout_.loops[id].size() > layout_.loops[definitionId(operand)].size()) {
          materialized_[operand.index] = true;
        }
      }
    }
  }

  bool isConstant(ValueId value) const {
    Opcode opcode = definition(value).opcode;
    return opcode == Opcode::Const || opcode == Opcode::ConstBool;
  }

  // The characters of a read of `value`'s variable: its own once the
  // variables are numbered, the estimate before.
  int readCharacters(ValueId value) const {
    if (!options_.readCharacters) {
      return 0;
    }
    int variable = allocation_.variableOfValue[value.index];
    return variable >= 0 ? options_.readCharacters(variable) : options_.estimatedReadCharacters;
  }

  // The shape of `instruction` written inline: from its operands' shapes,
  // and the variables it reads itself.
  InlineShape inlineShapeOf(const Instruction& instruction) const {
    std::vector<InlineShape> operands;
    int reads = 0;
    for (ValueId operand : instruction.operands) {
      operands.push_back(shapeOf(operand));
      if (materialized_[operand.index] && !isConstant(operand)) {
        reads += readCharacters(operand);
      }
    }
    InlineShape shape = options_.shape(function_, instruction, operands);
    shape.operations += reads;
    return shape;
  }

  InlineShape shapeOf(ValueId value) const {
    if (materialized_[value.index] || isConstant(value)) {
      return InlineShape{};
    }
    return inlineShapeOf(definition(value));
  }

  // The cost of one consumer: the deepest bracket nesting it writes, and
  // the operations written in its block.
  std::pair<int, int> cost(const Instruction& consumer) const {
    int depth = 0;
    int operations = 0;
    if (consumer.result.valid() && materialized_[consumer.result.index] &&
        consumer.opcode != Opcode::Loop && !isStatementOpcode(consumer.opcode)) {
      // `#n=expr`: the expression itself, unbracketed.
      InlineShape own = inlineShapeOf(consumer);
      return {own.bracketDepth, own.operations};
    }
    for (std::size_t i = 0; i < consumer.operands.size(); ++i) {
      InlineShape shape = shapeOf(consumer.operands[i]);
      int operandDepth = bracketedDepth(shape);
      if (consumer.opcode == Opcode::If) {
        operandDepth = shape.bracketDepth; // a condition brings its own brackets
      } else if (consumer.opcode == Opcode::Loop && i == 1) {
        operandDepth += 1; // `WHILE [#i LE bound]`
      } else if (isStatementOpcode(consumer.opcode)) {
        operandDepth += 1; // inside an `IF [..]` test
      }
      depth = std::max(depth, operandDepth);
      // One block holds them all. A variable read as a whole address
      // (`X#104`), or not written at all where the word is modal, is left
      // to the limit's room for the addresses.
      operations += shape.operations;
    }
    return {depth, operations};
  }

  // `#n=expr` has only its variable besides the expression; a move or a
  // test has addresses and words around it.
  int operationLimit(const Instruction& consumer) const {
    bool assignment = consumer.result.valid() && materialized_[consumer.result.index] &&
                      consumer.opcode != Opcode::Loop && !isStatementOpcode(consumer.opcode);
    return assignment && options_.maximumAssignmentOperations > 0
               ? options_.maximumAssignmentOperations
               : options_.maximumInlineOperations;
  }

  bool fits(const Instruction& consumer) const {
    auto [depth, operations] = cost(consumer);
    return depth <= options_.maximumBracketDepth && operations <= operationLimit(consumer);
  }

  // Moves the deepest inline value under `instruction` into a variable;
  // false when nothing below can move.
  bool materializeDeepest(const Instruction& instruction) {
    ValueId best;
    int bestScore = -1;
    for (ValueId operand : instruction.operands) {
      if (materialized_[operand.index] || isConstant(operand)) {
        continue;
      }
      InlineShape shape = shapeOf(operand);
      int score = bracketedDepth(shape) * 1000 + shape.operations;
      if (score > bestScore) {
        bestScore = score;
        best = operand;
      }
    }
    if (!best.valid()) {
      return false;
    }
    if (function_.valueTypes[best.index] != ValueType::F64) {
      return materializeDeepest(definition(best)); // a condition: shrink what it compares
    }
    materialized_[best.index] = true;
    fit(definitionId(best));
    return true;
  }

  void fit(InstructionId id) {
    const Instruction& consumer = function_.instructions[id];
    while (!fits(consumer)) {
      if (!materializeDeepest(consumer)) {
        auto [depth, operations] = cost(consumer);
        bool tooDeep = depth > options_.maximumBracketDepth;
        fail(tooDeep ? "bracket nesting" : "inline operations", tooDeep ? depth : operations,
             tooDeep ? options_.maximumBracketDepth : operationLimit(consumer),
             "an expression that cannot be split");
        return;
      }
    }
  }

  // A statement of its own: an effect, or a value computed into a variable.
  bool isConsumer(InstructionId id) const {
    const Instruction& instruction = function_.instructions[id];
    return needed_[id] && (!isPure(instruction.opcode) ||
                           (instruction.result.valid() && materialized_[instruction.result.index]));
  }

  void fitExpressions() {
    for (InstructionId id : layout_.order) {
      if (isConsumer(id)) {
        fit(id);
      }
    }
  }

  // The first numbering may leave a statement longer than its limit (a
  // read estimated as `#nn` is `#104`): what is too long moves more into
  // variables, and the variables are numbered again, until every statement
  // fits with the variables it reads. Materialising only grows, so this
  // ends; past a few rounds it is the limit's error.
  void fitNumberedStatements() {
    static constexpr int maximumRounds = 8;
    for (int round = 0; options_.readCharacters && result_.failures.empty(); ++round) {
      std::vector<InstructionId> tooLong;
      for (InstructionId id : layout_.order) {
        if (isConsumer(id) && !fits(function_.instructions[id])) {
          tooLong.push_back(id);
        }
      }
      if (tooLong.empty()) {
        return;
      }
      if (round == maximumRounds) {
        const Instruction& consumer = function_.instructions[tooLong.front()];
        fail("inline operations", cost(consumer).second, operationLimit(consumer),
             fmt::format("a statement, after numbering the variables {} times,", maximumRounds));
        return;
      }
      for (InstructionId id : tooLong) {
        fit(id);
      }
      if (result_.failures.empty()) {
        allocation_.variableOfValue.assign(function_.valueTypes.size(), -1);
        assignVariables();
      }
    }
  }

  std::optional<double> constantValue(ValueId value) const {
    return passes::constantValue(function_, value);
  }

  // A counting loop from a constant whose index has one reader, a product
  // i * c (c constant, the bounds constant) or i / high (the loop from 1 to
  // high, high in a variable): the product takes the index's variable,
  // which then steps by c (or 1 / high).
  void stepScaledLoops() {
    std::vector<int> readCount(function_.valueTypes.size(), 0);
    std::vector<InstructionId> reader(function_.valueTypes.size(), 0);
    for (InstructionId id = 0; id < function_.instructions.size(); ++id) {
      for (ValueId operand : function_.instructions[id].operands) {
        ++readCount[operand.index];
        reader[operand.index] = id;
      }
    }
    for (const Instruction& loop : function_.instructions) {
      if (loop.opcode != Opcode::Loop || loopAdvance(function_, loop).valid() ||
          !constantValue(loop.operands[0]) || readCount[loop.result.index] != 1 ||
          !materialized_[loop.result.index]) {
        continue;
      }
      const Instruction& product = function_.instructions[reader[loop.result.index]];
      if (std::optional<double> step = scaledStep(loop, product)) {
        loopOfProduct_[product.result.index] = loop.result.index;
        allocation_.stepOfLoop[loop.result.index] = *step;
        allocation_.steppedProducts.insert(product.result.index);
      }
    }
  }

  // What the loop's variable steps by when it holds `product`; NaN for
  // i / high; nothing when `product` is not a scaled index.
  std::optional<double> scaledStep(const Instruction& loop, const Instruction& product) const {
    std::optional<double> step;
    if (product.opcode == Opcode::Mul && constantValue(loop.operands[1])) {
      ValueId scale =
          product.operands[0] == loop.result ? product.operands[1] : product.operands[0];
      step = constantValue(scale);
    } else if (product.opcode == Opcode::Div && product.operands[0] == loop.result &&
               product.operands[1] == loop.operands[1] && *constantValue(loop.operands[0]) == 1 &&
               materialized_[loop.operands[1].index]) {
      step = std::numeric_limits<double>::quiet_NaN();
    }
    if (!step || *step == 0 || std::isinf(*step)) {
      return std::nullopt;
    }
    return step;
  }

  void fail(std::string limit, int needed, int available, std::string what) {
    for (const AllocationFailure& failure : result_.failures) {
      if (failure.limit == limit) {
        return;
      }
    }
    result_.failures.push_back(
        {limit, needed, available,
         fmt::format("{} needs {} {}, the controller allows {}", what, needed, limit, available)});
  }

  // The last position at which `value` is read, the loops it is read in
  // counted as a whole.
  void recordUse(ValueId value, int position, const std::vector<InstructionId>& loops) {
    if (isConstant(value)) {
      return;
    }
    const Instruction& instruction = definition(value);
    if (!materialized_[value.index]) {
      for (ValueId operand : instruction.operands) {
        recordUse(operand, position, loops); // an inline value reads its operands where it is used
      }
      return;
    }
    // A loop's variable is defined inside its own loop: a read in its body
    // is not a read from an outer value, kept to the loop's end (the loop
    // keeps a counting variable alive to its end itself).
    std::size_t definedDepth =
        layout_.loops[definitionId(value)].size() + (instruction.opcode == Opcode::Loop ? 1 : 0);
    if (loops.size() > definedDepth) {
      position = std::max(position, layout_.loopEnd.at(loops[definedDepth]));
    }
    lastUse_[value.index] = std::max(lastUse_[value.index], position);
  }

  void computeLiveness() {
    lastUse_.assign(function_.valueTypes.size(), -1);
    for (InstructionId id : layout_.order) {
      if (!needed_[id]) {
        continue;
      }
      const Instruction& instruction = function_.instructions[id];
      if (instruction.result.valid() && materialized_[instruction.result.index]) {
        recordUse(instruction.result, layout_.position[id], layout_.loops[id]);
      }
      if (instruction.result.valid() && materialized_[instruction.result.index] == false &&
          isPure(instruction.opcode)) {
        continue; // inline: its operands are read where it is used
      }
      int position = layout_.position[id] + (isStatementOpcode(instruction.opcode) ? 1 : 0);
      for (std::size_t i = 0; i < instruction.operands.size(); ++i) {
        bool bound = instruction.opcode == Opcode::Loop && i == 1;
        recordUse(instruction.operands[i], bound ? layout_.loopEnd.at(id) : position,
                  layout_.loops[id]);
      }
      // A counting loop reads its variable at its end (`#i=#i+1`); an
      // advancing one only writes it there (`#u=#next`), so its value may
      // take the variable once the body has read it for the last time.
      if (instruction.opcode == Opcode::Loop && !loopAdvance(function_, instruction).valid()) {
        lastUse_[instruction.result.index] =
            std::max(lastUse_[instruction.result.index], layout_.loopEnd.at(id));
      }
    }
  }

  // The variables free for values, in preference order, after the
  // parameters and the tables have taken theirs.
  std::vector<int> assignTables(std::set<int>& taken) {
    for (int variable : options_.parameterVariables) {
      taken.insert(variable);
    }
    allocation_.parameterVariables = options_.parameterVariables;
    allocation_.tableBase.assign(function_.tables.size(), -1);
    std::vector<bool> tableUsed(function_.tables.size(), false);
    for (InstructionId id : layout_.order) {
      const Instruction& instruction = function_.instructions[id];
      if (needed_[id] && instruction.opcode == Opcode::TableLoad &&
          instruction.index < tableUsed.size()) {
        tableUsed[instruction.index] = true;
      }
    }
    // The largest first: they need the longest runs.
    std::vector<std::size_t> order;
    for (std::size_t table = 0; table < function_.tables.size(); ++table) {
      if (tableUsed[table]) {
        order.push_back(table);
      }
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return function_.tables[a].size() > function_.tables[b].size();
    });
    for (std::size_t i = 0; i < order.size(); ++i) {
      std::size_t table = order[i];
      // Equal tables (one per pass of a cut) share their variables.
      auto equal = std::find_if(
          order.begin(), order.begin() + static_cast<std::ptrdiff_t>(i),
          [&](std::size_t other) { return function_.tables[other] == function_.tables[table]; });
      if (equal != order.begin() + static_cast<std::ptrdiff_t>(i)) {
        allocation_.tableBase[table] = allocation_.tableBase[*equal];
      } else {
        placeTable(table, taken);
      }
    }
    std::vector<int> free;
    for (const VariableSpan& span : options_.variables) {
      for (int variable = span.first; variable <= span.last; ++variable) {
        if (!taken.contains(variable)) {
          free.push_back(variable);
        }
      }
    }
    return free;
  }

  void placeTable(std::size_t table, std::set<int>& taken) {
    int size = static_cast<int>(function_.tables[table].size());
    for (const VariableSpan& span : options_.variables) {
      int runStart = span.first;
      for (int variable = span.first; variable <= span.last; ++variable) {
        if (taken.contains(variable)) {
          runStart = variable + 1;
        } else if (variable - runStart + 1 == size) {
          allocation_.tableBase[table] = runStart;
          for (int v = runStart; v <= variable; ++v) {
            taken.insert(v);
          }
          return;
        }
      }
    }
    if (size == 0) {
      return;
    }
    fail("consecutive variables", size, longestFreeRun(taken),
         fmt::format("table {} of {} values", table, size));
  }

  int longestFreeRun(const std::set<int>& taken) const {
    int longest = 0;
    for (const VariableSpan& span : options_.variables) {
      int run = 0;
      for (int variable = span.first; variable <= span.last; ++variable) {
        run = taken.contains(variable) ? 0 : run + 1;
        longest = std::max(longest, run);
      }
    }
    return longest;
  }

  struct Interval {
    int start;
    int end;
    ValueId value;
  };

  // Linear scan over the live intervals: the lowest free variable in
  // preference order, freed once its value is dead.
  void assignVariables() {
    computeLiveness();
    std::set<int> taken;
    std::vector<int> free = assignTables(taken);
    int reserved = static_cast<int>(taken.size()); // parameters and tables
    std::vector<Interval> intervals;
    for (InstructionId id : layout_.order) {
      const Instruction& instruction = function_.instructions[id];
      if (needed_[id] && instruction.result.valid() && materialized_[instruction.result.index] &&
          instruction.opcode != Opcode::Param) {
        int start = layout_.position[id];
        intervals.push_back(
            {start, std::max(start, lastUse_[instruction.result.index]), instruction.result});
      }
    }
    std::stable_sort(intervals.begin(), intervals.end(),
                     [](const Interval& a, const Interval& b) { return a.start < b.start; });
    std::set<std::size_t> freeSlots; // indices into `free`; beyond it: variables that do not exist
    std::size_t slotCount = 0;
    // The value an advancing loop's variable takes next goes to the
    // variable's own slot, kept for it once the variable's last read is
    // past: no `#u=#next` at the loop's end.
    std::map<std::uint32_t, std::uint32_t> nextOfVariable; // loop variable -> next value
    for (InstructionId id : layout_.order) {
      const Instruction& instruction = function_.instructions[id];
      // Only for a next value that gets a slot after the variable's: one
      // the body computes into a variable (not inline, not from outside).
      ValueId next = loopAdvance(function_, instruction);
      if (next.valid() && needed_[id] && materialized_[next.index] &&
          std::ranges::count(layout_.loops[definitionId(next)], id) > 0) {
        nextOfVariable[instruction.result.index] = next.index;
      }
    }
    std::map<std::uint32_t, std::size_t> slotOfValue;
    std::map<std::uint32_t, std::size_t> reservedSlots; // next value -> its loop variable's slot
    using Active = std::tuple<int, std::size_t, std::uint32_t>; // (end, slot, value)
    std::priority_queue<Active, std::vector<Active>, std::greater<>> active;
    for (const Interval& interval : intervals) {
      while (!active.empty() && std::get<0>(active.top()) <= interval.start) {
        auto [end, freed, value] = active.top();
        active.pop();
        // Kept for the value the loop variable advances to, if still to come.
        if (auto next = nextOfVariable.find(value);
            next != nextOfVariable.end() && !slotOfValue.contains(next->second)) {
          reservedSlots[next->second] = freed;
        } else {
          freeSlots.insert(freed);
        }
      }
      std::size_t slot;
      if (auto reserved = reservedSlots.find(interval.value.index);
          reserved != reservedSlots.end()) {
        slot = reserved->second;
        reservedSlots.erase(reserved);
      } else if (freeSlots.empty()) {
        slot = slotCount++;
      } else {
        slot = *freeSlots.begin();
        freeSlots.erase(freeSlots.begin());
      }
      slotOfValue[interval.value.index] = slot;
      active.push({interval.end, slot, interval.value.index});
      // A stepped product keeps a slot of its own through its life, unused:
      // giving it to the values made meanwhile would save a variable but
      // renumber theirs.
      if (slot < free.size() && !loopOfProduct_.contains(interval.value.index)) {
        allocation_.variableOfValue[interval.value.index] = free[slot];
        taken.insert(free[slot]);
      }
    }
    for (auto [product, loop] : loopOfProduct_) {
      allocation_.variableOfValue[product] = allocation_.variableOfValue[loop];
    }
    for (std::size_t i = 0; i < options_.parameterVariables.size(); ++i) {
      for (InstructionId id : layout_.order) {
        const Instruction& instruction = function_.instructions[id];
        if (instruction.opcode == Opcode::Param && instruction.index == i) {
          allocation_.variableOfValue[instruction.result.index] = options_.parameterVariables[i];
        }
      }
    }
    if (slotCount > free.size()) {
      fail("variables", reserved + static_cast<int>(slotCount),
           reserved + static_cast<int>(free.size()), "the program");
    }
    allocation_.usedVariables.assign(taken.begin(), taken.end());
  }

  const Function& function_;
  AllocationOptions options_;
  ProgramLayout layout_;
  std::vector<bool> needed_;
  std::vector<bool> materialized_;
  std::vector<int> useCount_;
  std::vector<int> lastUse_;
  std::map<std::uint32_t, std::uint32_t> loopOfProduct_; // stepped product -> its loop index
  Allocation allocation_;
  AllocationResult result_;
};

} // namespace

AllocationResult allocateVariables(const Function& function, const AllocationOptions& options) {
  return Allocator(function, options).run();
}

std::map<int, std::vector<std::size_t>> tablesByBase(const Function& function,
                                                     const Allocation& allocation) {
  std::map<int, std::vector<std::size_t>> tables;
  for (std::size_t table = 0; table < function.tables.size(); ++table) {
    if (allocation.tableBase[table] >= 0) {
      tables[allocation.tableBase[table]].push_back(table);
    }
  }
  return tables;
}

} // namespace cncc::ir
