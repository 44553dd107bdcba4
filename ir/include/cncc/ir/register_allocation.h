// Register allocation: which IR values of a Function live in numbered
// controller variables (`#n`), and which are printed inline as bracket
// expressions where they are used.
//
// A value gets a variable when it must: a loop's induction variable, a part
// parameter (fixed by the caller), a value used more than once, a value
// defined outside a loop and used inside it (computed once, not every
// iteration), the result of an operation the caller says needs statements
// of its own, and an operand whose inline expression would exceed the
// bracket-nesting or length limit of the expression that uses it. Every
// other pure value is inline. Tables get blocks of consecutive variables,
// filled at the start and live for the whole program.
//
// Liveness is computed over the structured regions: a value used inside a
// loop body but defined outside is live through the whole loop, so its
// variable is not reused before the loop ends. A variable is reused once
// its value is dead (a statement may read a variable and write its result
// to the same one).
//
// With stepScaledLoops, a counting loop whose index is only read scaled
// (u = i * c, or u = i / high for a loop from 1 to high) has u itself in
// its variable, stepped by c (or 1 / high): the product shares the index's
// variable and is computed by no statement.
//
// The IR knows nothing about controllers: the caller describes the
// variables, the limits and its expression syntax (InlineShapeFunction).
#pragma once

#include "cncc/ir/ir.h"

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <span>
#include <string>
#include <vector>

namespace cncc::ir {

// Variables `#first` to `#last` inclusive.
struct VariableSpan {
  int first = 0;
  int last = -1;
};

// How an expression is written, seen from the expression that uses it.
enum class InlineForm {
  Atom,           // a number, `#5`, `#[100+#3]`, `SIN[..]`, `[..]`: never needs brackets
  Additive,       // `a+b`, `a-b`
  Multiplicative, // `a*b`, `a/b`
  Negation,       // `-a`
};

struct InlineShape {
  int bracketDepth = 0; // bracket levels inside the text
  InlineForm form = InlineForm::Atom;
  int operations = 0; // operations written in the text (a length measure)
};

// The shape of `instruction` printed inline, from the shapes of its
// operands (a value in a variable or a constant has the default shape).
using InlineShapeFunction =
    std::function<InlineShape(const Function&, const Instruction&, std::span<const InlineShape>)>;

struct AllocationOptions {
  // Variables free for values and tables, in the order they are preferred.
  std::vector<VariableSpan> variables;
  // The variable of each part parameter (fixed; never given to anything else).
  std::vector<int> parameterVariables;
  // Limits of one inline expression, as the uses count them: the statement
  // `#n=expr` counts expr's depth; an address word `X[..]`, a loop bound
  // and an operand written twice count the bracketed depth.
  int maximumBracketDepth = 5;
  int maximumInlineOperations = 10;
  // The same limit for the expression of a `#n=expr` statement (0: as above).
  int maximumAssignmentOperations = 0;
  InlineShapeFunction shape; // empty: every operation adds a bracket level
  // The characters a read of a variable adds to a statement (`#104`: 4),
  // counted with the operations; empty: reads add nothing. Until the
  // variables are numbered a read counts `estimatedReadCharacters`; then
  // its own, and a statement that turns out too long moves more values
  // into variables before they are numbered again.
  std::function<int(int variable)> readCharacters;
  int estimatedReadCharacters = 0;
  // Operations printed as several statements (min, max, select, ..): their
  // result always gets a variable, and their operands are written twice.
  std::vector<Opcode> statementOpcodes;
  // Loops whose index is only read scaled hold the scaled value (see above).
  bool stepScaledLoops = false;
};

struct Allocation {
  // The variable of each value; -1 when it is printed inline (or unused).
  std::vector<int> variableOfValue;
  // The first variable of each table's block; -1 when the table is unused.
  std::vector<int> tableBase;
  std::vector<int> parameterVariables;
  // Every variable the program uses, ascending, tables included.
  std::vector<int> usedVariables;
  // The loops stepped by their scale: loop index value -> what its variable
  // advances by each pass, c for u = i * c; NaN for u = i / high, which
  // advances by 1 / high.
  std::map<std::uint32_t, double> stepOfLoop;
  // The products those variables hold (each shares its loop's variable).
  std::set<std::uint32_t> steppedProducts;

  bool inVariable(ValueId value) const { return variableOfValue[value.index] >= 0; }
  bool isSteppedProduct(ValueId value) const { return steppedProducts.contains(value.index); }
};

// The tables by the first variable of their block: equal tables (one per
// pass of a cut) share one block, so a printer writes each block once.
std::map<int, std::vector<std::size_t>> tablesByBase(const Function& function,
                                                     const Allocation& allocation);

// Why a Function does not fit: the limit and the count it needed.
struct AllocationFailure {
  std::string limit; // "variables", "bracket nesting", ...
  int needed = 0;
  int available = 0;
  std::string message;
};

struct AllocationResult {
  Allocation allocation;
  std::vector<AllocationFailure> failures; // empty on success
  bool ok() const { return failures.empty(); }
};

AllocationResult allocateVariables(const Function& function, const AllocationOptions& options);

// The depth an inline expression of this shape adds where it must be
// bracketed (as an address word, a loop bound, a function argument list).
int bracketedDepth(const InlineShape& shape);

} // namespace cncc::ir
