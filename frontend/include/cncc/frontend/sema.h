// Semantic analysis: imports, name resolution and scopes, types, builtin
// signatures, compile-time evaluation of `const` and `fn`, and the geometric
// checks a user needs before anything is generated.
//
// `checkProgram` loads the main file and its imports, checks everything and
// returns the annotated program; problems go to the DiagnosticEngine and
// never stop the check.
#pragma once

#include "cncc/frontend/ast.h"
#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/frontend/value.h"

#include <deque>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::frontend {

enum class DeclarationKind {
  Constant,          // const name = ...
  Function,          // fn name(...) = ...
  PartParameter,     // part p(name = default)
  FunctionParameter, // fn f(name)
  Let,               // let name = ...
  LoopVariable,      // for name in ...
  CurveParameter,    // t inside polar(...) and param(...)
  Builtin,           // sin, nurbs, pi, ...
  Part,              // part name(...) { ... }
};

std::string_view declarationKindName(DeclarationKind kind);

struct Declaration {
  DeclarationKind kind;
  std::string name;
  SourceSpan span; // the defining name; invalid for builtins
  Type type;
  // Constants: their value. Part parameters: the value used for checks (the
  // default or a -D override). Lets: the value with parameters at defaults,
  // when it could be computed.
  std::optional<Value> value;
  // Functions and builtins: `nurbs(order | degree, points, weights?, knots?)`.
  std::string signature;
  std::string description; // one line, for hovers
  const FnItem* function = nullptr;
  const PartItem* part = nullptr;
};

// A use or a definition of a name, for hovers and go-to-definition.
struct Reference {
  SourceSpan span;
  const Declaration* declaration;
  bool isDefinition;
};

// -D name=value overrides of part parameter defaults, found by a view of
// the parameter's name.
using ParameterDefines = std::map<std::string, double, std::less<>>;

struct CheckOptions {
  // Directories searched for `import "..."` after the importing file's own
  // directory, in order (-I dirs, then the stdlib directory).
  std::vector<std::string> importPaths;
  // -D name=value overrides of part parameter defaults.
  ParameterDefines defines;
  // -p NAME; when empty and the file holds one part, that part.
  std::string partName;
  // Whether a missing or ambiguous part is an error (compiling needs one
  // part; `cncc check` checks every part).
  bool requirePart = false;
  // Threads for a large file: 0 uses a second one when the machine has two
  // cores, 1 none, 2 a second one always. The result is the same in every
  // case.
  unsigned threads = 0;
  // The steps compile-time evaluation may take in all before it stops
  // (silently: it guards against pathological sources).
  std::size_t evaluationSteps = 20'000'000;
};

struct CheckedProgram {
  CheckedProgram() = default;
  CheckedProgram(CheckedProgram&&) = default;
  CheckedProgram& operator=(CheckedProgram&&) = default;

  std::deque<Module> modules; // the main file first, then its imports
  // A list: declarations made on two threads are joined without moving.
  std::list<Declaration> declarations;
  std::vector<Reference> references;
  std::vector<const PartItem*> parts;     // of the main file
  const PartItem* selectedPart = nullptr; // per CheckOptions::partName

  // The innermost reference whose span contains `offset` in `file`.
  const Reference* referenceAt(FileId file, std::uint32_t offset) const;
  // Names visible at a position (for completion): builtins, file-level items,
  // and the parameters, lets and loop variables in scope there.
  std::vector<const Declaration*> visibleAt(FileId file, std::uint32_t offset) const;

  // Where each scoped declaration is visible (parameters, lets, loop
  // variables, `t`), for visibleAt.
  struct ScopeExtent {
    SourceSpan span;
    const Declaration* declaration;
  };
  std::vector<ScopeExtent> scopeExtents;
};

CheckedProgram checkProgram(SourceManager& sources, FileId mainFile, const CheckOptions& options,
                            DiagnosticEngine& diagnostics);

// Evaluates expressions of a checked program afterwards: a curve's r(t) at
// many t, a let at other parameter values. Problems give an Error value
// and a diagnostic in `diagnostics`.
class ExpressionEvaluator {
public:
  ExpressionEvaluator(const CheckedProgram& program, DiagnosticEngine& diagnostics);
  ~ExpressionEvaluator();
  ExpressionEvaluator(const ExpressionEvaluator&) = delete;
  ExpressionEvaluator& operator=(const ExpressionEvaluator&) = delete;

  Value evaluate(const Expr& expression, const Environment& environment);

private:
  struct State;
  std::unique_ptr<State> state_;
};

// The builtin functions and constants, for completion and documentation.
struct BuiltinParameter {
  std::string name;
  bool required;
};
struct BuiltinInfo {
  std::string name;
  std::vector<BuiltinParameter> parameters; // empty with `variadic` for path(...)
  bool variadic = false;
  std::string signature;
  std::string description;
};
const std::vector<BuiltinInfo>& builtinFunctions();

// The argument expression a call of a builtin binds to its parameter
// `name` (by name, or by position in the builtin's order), as evaluation
// binds them; nullptr when the call does not give it.
const Expr* builtinArgument(const CallExpr& call, std::string_view name);

} // namespace cncc::frontend
