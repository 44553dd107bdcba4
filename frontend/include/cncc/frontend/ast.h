// The abstract syntax tree. The parser builds it; the semantic checker
// annotates it (types, resolved declarations); the formatter, the language
// server and the lowering to IR read it.
//
// A broken source still produces a tree: what could not be parsed becomes an
// Error node, so later phases and the editor keep working on the rest.
#pragma once

#include "cncc/frontend/lexer.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/frontend/types.h"

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cncc::frontend {

struct Declaration;

// The nodes of one module hold no resources of their own, so that freeing
// a tree is freeing its module's arena, without a visit of every node:
//  - names and strings (of declarations, references, arguments, members,
//    string literals, imports) view the text of their file, or the
//    unescaped copy of a string the file keeps, which its SourceManager
//    keeps: a tree must not outlive the SourceManager it was parsed from;
//  - children are in the module's arena (node_arena.h): a few large blocks
//    instead of an allocation per node, freed when the module goes.
// A pointer to a node or a list of nodes marks the parent-child relation
// and moves like a unique_ptr, but destroys nothing: a member that must be
// destroyed (a std::string, a std::vector) would leak. Nodes are not
// polymorphic (no virtual destructor, as none is destroyed) and their kinds
// are a byte: a file of 50,000 lines has some 700,000 of them, which the
// checker and the evaluator read again, so their size is cache misses.
class NodeArena;
struct NodeDeleter {
  template <typename Node> void operator()(Node* /*node*/) const {}
};

// The children of a node (arguments, components, statements), placed in the
// module's arena at their final number: read like a vector, and the
// elements can be changed, but none added or removed. The arena frees the
// memory; the elements are not destroyed (see NodeDeleter).
template <typename Element> class NodeList {
public:
  NodeList() = default;
  NodeList(Element* elements, std::size_t size) : elements_(elements), size_(size) {}
  NodeList(NodeList&& other) noexcept
      : elements_(std::exchange(other.elements_, nullptr)), size_(std::exchange(other.size_, 0)) {}
  NodeList& operator=(NodeList&& other) noexcept {
    if (this != &other) {
      elements_ = std::exchange(other.elements_, nullptr);
      size_ = std::exchange(other.size_, 0);
    }
    return *this;
  }
  NodeList(const NodeList&) = delete;
  NodeList& operator=(const NodeList&) = delete;
  ~NodeList() = default;

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  Element* begin() { return elements_; }
  Element* end() { return elements_ + size_; }
  const Element* begin() const { return elements_; }
  const Element* end() const { return elements_ + size_; }
  Element& operator[](std::size_t index) { return elements_[index]; }
  const Element& operator[](std::size_t index) const { return elements_[index]; }
  Element& front() { return elements_[0]; }
  const Element& front() const { return elements_[0]; }
  Element& back() { return elements_[size_ - 1]; }
  const Element& back() const { return elements_[size_ - 1]; }

private:
  Element* elements_ = nullptr;
  std::size_t size_ = 0;
};

// ----------------------------------------------------------------------------
// Expressions

enum class ExprKind : std::uint8_t {
  Number, // 12, 2.5mm, 45deg
  Bool,   // true, false
  String, // "std/curves"
  Name,   // P, depth, pi, t
  Unary,  // -x, !c
  Binary, // a + b, a < b, a && b
  Call,   // nurbs(order=4, points=P), sin(t), lobes(3, t)
  Point,  // (x, y) or (x, y, z)
  List,   // [1, 2, 3]
  Range,  // a .. b
  Index,  // L[i]
  Member, // p.x
  IfElse, // if c then a else b
  Error,  // what could not be parsed
};

enum class UnaryOperator : std::uint8_t { Negate, Not };
enum class BinaryOperator : std::uint8_t {
  Add,
  Subtract,
  Multiply,
  Divide,
  Remainder,
  Power,
  Equal,
  NotEqual,
  Less,
  LessEqual,
  Greater,
  GreaterEqual,
  And,
  Or,
};

std::string_view operatorSpelling(BinaryOperator op);

struct Expr {
  explicit Expr(ExprKind kind, SourceSpan span) : kind(kind), span(span) {}
  Expr(const Expr&) = delete;
  Expr& operator=(const Expr&) = delete;

  ExprKind kind;
  Type type; // set by the semantic checker (two bytes, beside the kind)
  SourceSpan span;
};
using ExprPtr = std::unique_ptr<Expr, NodeDeleter>;

struct NumberExpr : Expr {
  NumberExpr(SourceSpan span, double value, UnitSuffix unit)
      : Expr(ExprKind::Number, span), value(value), unit(unit) {}
  double value; // with the unit applied (mm, rad)
  UnitSuffix unit;
};

struct BoolExpr : Expr {
  BoolExpr(SourceSpan span, bool value) : Expr(ExprKind::Bool, span), value(value) {}
  bool value;
};

struct StringExpr : Expr {
  StringExpr(SourceSpan span, std::string_view value)
      : Expr(ExprKind::String, span), value(value) {}
  std::string_view value;
};

struct NameExpr : Expr {
  NameExpr(SourceSpan span, std::string_view name) : Expr(ExprKind::Name, span), name(name) {}
  std::string_view name;
  const Declaration* declaration = nullptr; // set by the semantic checker
};

struct UnaryExpr : Expr {
  UnaryExpr(SourceSpan span, UnaryOperator op, ExprPtr operand)
      : Expr(ExprKind::Unary, span), op(op), operand(std::move(operand)) {}
  UnaryOperator op;
  ExprPtr operand;
};

struct BinaryExpr : Expr {
  BinaryExpr(SourceSpan span, BinaryOperator op, SourceSpan operatorSpan, ExprPtr left,
             ExprPtr right)
      : Expr(ExprKind::Binary, span), op(op), operatorSpan(operatorSpan), left(std::move(left)),
        right(std::move(right)) {}
  BinaryOperator op;
  SourceSpan operatorSpan;
  ExprPtr left;
  ExprPtr right;
};

// `name = value` or a positional `value`, in a call or a statement.
struct Argument {
  std::string_view name; // empty when positional
  SourceSpan nameSpan;
  ExprPtr value;
  SourceSpan span() const { return name.empty() ? value->span : nameSpan.to(value->span); }
};

struct CallExpr : Expr {
  CallExpr(SourceSpan span, std::string_view callee, SourceSpan calleeSpan,
           NodeList<Argument> arguments)
      : Expr(ExprKind::Call, span), callee(callee), calleeSpan(calleeSpan),
        arguments(std::move(arguments)) {}
  std::string_view callee;
  SourceSpan calleeSpan;
  NodeList<Argument> arguments;
  const Declaration* declaration = nullptr; // the fn or builtin, set by the checker
  // polar(...) and param(...): the declaration of their `t`, set by the checker.
  const Declaration* curveParameter = nullptr;
  // The argument list ended at a syntax error: arguments after it were never
  // read, so the checker does not call them missing.
  bool argumentsCutShort = false;
};

struct PointExpr : Expr {
  PointExpr(SourceSpan span, NodeList<ExprPtr> components)
      : Expr(ExprKind::Point, span), components(std::move(components)) {}
  NodeList<ExprPtr> components; // two or three
};

struct ListExpr : Expr {
  ListExpr(SourceSpan span, NodeList<ExprPtr> elements)
      : Expr(ExprKind::List, span), elements(std::move(elements)) {}
  NodeList<ExprPtr> elements;
};

struct RangeExpr : Expr {
  RangeExpr(SourceSpan span, ExprPtr low, ExprPtr high)
      : Expr(ExprKind::Range, span), low(std::move(low)), high(std::move(high)) {}
  ExprPtr low;
  ExprPtr high;
};

struct IndexExpr : Expr {
  IndexExpr(SourceSpan span, ExprPtr base, ExprPtr index)
      : Expr(ExprKind::Index, span), base(std::move(base)), index(std::move(index)) {}
  ExprPtr base;
  ExprPtr index;
};

struct MemberExpr : Expr {
  MemberExpr(SourceSpan span, ExprPtr base, std::string_view member, SourceSpan memberSpan)
      : Expr(ExprKind::Member, span), base(std::move(base)), member(member),
        memberSpan(memberSpan) {}
  ExprPtr base;
  std::string_view member;
  SourceSpan memberSpan;
};

struct IfElseExpr : Expr {
  IfElseExpr(SourceSpan span, ExprPtr condition, ExprPtr thenValue, ExprPtr elseValue)
      : Expr(ExprKind::IfElse, span), condition(std::move(condition)),
        thenValue(std::move(thenValue)), elseValue(std::move(elseValue)) {}
  ExprPtr condition;
  ExprPtr thenValue;
  ExprPtr elseValue;
};

struct ErrorExpr : Expr {
  explicit ErrorExpr(SourceSpan span) : Expr(ExprKind::Error, span) {}
};

// ----------------------------------------------------------------------------
// Statements of a part body

enum class StmtKind : std::uint8_t {
  Units,   // units mm | inch
  Tool,    // tool N diameter=D [length=H] [radius=R] [spindle=S] [feed=F]
  Feed,    // feed F
  Spindle, // spindle S
  Safe,    // safe z=Z
  Origin,  // origin G54 .. G59 | origin G54.1 P<n>
  Coolant, // coolant flood | mist | through | off
  Let,     // let name = expr
  Cut,     // curve <expr> [modifiers]
  For,     // for i in a .. b { ... }
  If,      // if cond { ... } else { ... }
  Error,   // what could not be parsed
};

struct Stmt {
  explicit Stmt(StmtKind kind, SourceSpan span) : kind(kind), span(span) {}
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;

  StmtKind kind;
  SourceSpan span;
};
using StmtPtr = std::unique_ptr<Stmt, NodeDeleter>;

struct Block {
  SourceSpan span; // from '{' to '}'
  NodeList<StmtPtr> statements;
};

struct UnitsStmt : Stmt {
  UnitsStmt(SourceSpan span, std::string_view unit, SourceSpan unitSpan)
      : Stmt(StmtKind::Units, span), unit(unit), unitSpan(unitSpan) {}
  std::string_view unit; // "mm" or "inch"
  SourceSpan unitSpan;
};

struct ToolStmt : Stmt {
  ToolStmt(SourceSpan span, ExprPtr number, NodeList<Argument> settings)
      : Stmt(StmtKind::Tool, span), number(std::move(number)), settings(std::move(settings)) {}
  ExprPtr number;
  NodeList<Argument> settings; // diameter=, length=, radius=, spindle=, feed=
};

// `feed F` and `spindle S`.
struct ValueStmt : Stmt {
  ValueStmt(StmtKind kind, SourceSpan span, ExprPtr value)
      : Stmt(kind, span), value(std::move(value)) {}
  ExprPtr value;
};

struct SafeStmt : Stmt {
  SafeStmt(SourceSpan span, NodeList<Argument> settings)
      : Stmt(StmtKind::Safe, span), settings(std::move(settings)) {}
  NodeList<Argument> settings; // z=
};

// `origin G55` or `origin G54.1 P3`: the work offset the moves after it are
// in. The parser makes one only for a valid offset, so the fields are always
// in range.
struct OriginStmt : Stmt {
  OriginStmt(SourceSpan span, int group, int extended, SourceSpan offsetSpan,
             SourceSpan extendedSpan)
      : Stmt(StmtKind::Origin, span), group(group), extended(extended), offsetSpan(offsetSpan),
        extendedSpan(extendedSpan) {}
  int group = 54;          // 54 .. 59: G54 .. G59
  int extended = 0;        // 0: none; else n of `G54.1 Pn` (group is then 54)
  SourceSpan offsetSpan;   // `G55`, or `G54.1`
  SourceSpan extendedSpan; // `P3`; invalid when extended is 0
};

enum class CoolantMode : std::uint8_t { Off, Flood, Mist, Through };

// `coolant flood`: holds until the next `coolant`.
struct CoolantStmt : Stmt {
  CoolantStmt(SourceSpan span, CoolantMode mode, SourceSpan modeSpan)
      : Stmt(StmtKind::Coolant, span), mode(mode), modeSpan(modeSpan) {}
  CoolantMode mode = CoolantMode::Off;
  SourceSpan modeSpan;
};

// The words of `coolant`, and of `origin`'s offset as the formatter prints
// them ("G54", "G54.1").
std::string_view coolantModeSpelling(CoolantMode mode);
std::string originOffsetSpelling(const OriginStmt& origin);

struct LetStmt : Stmt {
  LetStmt(SourceSpan span, std::string_view name, SourceSpan nameSpan, ExprPtr value)
      : Stmt(StmtKind::Let, span), name(name), nameSpan(nameSpan), value(std::move(value)) {}
  std::string_view name;
  SourceSpan nameSpan;
  ExprPtr value;
  const Declaration* declaration = nullptr;
};

// A modifier after `curve <expr>`: a word alone (`sweep`) or `word=value`.
struct Modifier {
  std::string_view name;
  SourceSpan nameSpan;
  ExprPtr value; // null for a bare word
  SourceSpan span() const { return value ? nameSpan.to(value->span) : nameSpan; }
};

// The modifiers allowed after `curve <expr>`.
const std::vector<std::string>& cutModifierNames();

struct CutStmt : Stmt {
  CutStmt(SourceSpan span, ExprPtr curve, NodeList<Modifier> modifiers)
      : Stmt(StmtKind::Cut, span), curve(std::move(curve)), modifiers(std::move(modifiers)) {}
  ExprPtr curve;
  NodeList<Modifier> modifiers;
};

struct ForStmt : Stmt {
  ForStmt(SourceSpan span, std::string_view variable, SourceSpan variableSpan, ExprPtr range,
          Block body)
      : Stmt(StmtKind::For, span), variable(variable), variableSpan(variableSpan),
        range(std::move(range)), body(std::move(body)) {}
  std::string_view variable;
  SourceSpan variableSpan;
  ExprPtr range;
  Block body;
  const Declaration* declaration = nullptr;
};

struct IfStmt : Stmt {
  IfStmt(SourceSpan span, ExprPtr condition, Block thenBlock, Block elseBlock, bool hasElse)
      : Stmt(StmtKind::If, span), condition(std::move(condition)), thenBlock(std::move(thenBlock)),
        elseBlock(std::move(elseBlock)), hasElse(hasElse) {}
  ExprPtr condition;
  Block thenBlock;
  Block elseBlock; // `else if` becomes an else block holding one IfStmt
  bool hasElse;
};

struct ErrorStmt : Stmt {
  explicit ErrorStmt(SourceSpan span) : Stmt(StmtKind::Error, span) {}
};

// ----------------------------------------------------------------------------
// Top-level items

enum class ItemKind : std::uint8_t { Import, Const, Fn, Part, Error };

struct Item {
  explicit Item(ItemKind kind, SourceSpan span) : kind(kind), span(span) {}
  Item(const Item&) = delete;
  Item& operator=(const Item&) = delete;

  ItemKind kind;
  SourceSpan span;
};
using ItemPtr = std::unique_ptr<Item, NodeDeleter>;

struct ImportItem : Item {
  ImportItem(SourceSpan span, std::string_view path, SourceSpan pathSpan)
      : Item(ItemKind::Import, span), path(path), pathSpan(pathSpan) {}
  std::string_view path;
  SourceSpan pathSpan;
  FileId resolvedFile; // set by the module loader
};

struct ConstItem : Item {
  ConstItem(SourceSpan span, std::string_view name, SourceSpan nameSpan, ExprPtr value)
      : Item(ItemKind::Const, span), name(name), nameSpan(nameSpan), value(std::move(value)) {}
  std::string_view name;
  SourceSpan nameSpan;
  ExprPtr value;
  const Declaration* declaration = nullptr;
};

// A parameter of a fn (no default) or of a part (with a default).
struct Parameter {
  std::string_view name;
  SourceSpan nameSpan;
  ExprPtr defaultValue; // null when absent
  const Declaration* declaration = nullptr;
};

struct FnItem : Item {
  FnItem(SourceSpan span, std::string_view name, SourceSpan nameSpan,
         NodeList<Parameter> parameters, ExprPtr body)
      : Item(ItemKind::Fn, span), name(name), nameSpan(nameSpan), parameters(std::move(parameters)),
        body(std::move(body)) {}
  std::string_view name;
  SourceSpan nameSpan;
  NodeList<Parameter> parameters;
  ExprPtr body;
  const Declaration* declaration = nullptr;
};

struct PartItem : Item {
  PartItem(SourceSpan span, std::string_view name, SourceSpan nameSpan,
           NodeList<Parameter> parameters, Block body)
      : Item(ItemKind::Part, span), name(name), nameSpan(nameSpan),
        parameters(std::move(parameters)), body(std::move(body)) {}
  std::string_view name;
  SourceSpan nameSpan;
  NodeList<Parameter> parameters;
  Block body;
};

struct ErrorItem : Item {
  explicit ErrorItem(SourceSpan span) : Item(ItemKind::Error, span) {}
};

// One parsed file.
struct Module {
  FileId file;
  // Declared first: they outlive the items. A module joined from several
  // parsed ranges (appendModule) holds one arena per range.
  std::vector<std::shared_ptr<NodeArena>> arenas;
  std::vector<ItemPtr> items;
};

// Joins two modules of the same file: `from`'s items follow `into`'s, and
// `into` takes `from`'s arenas so the items stay valid (parser.cpp).
void appendModule(Module& into, Module&& from);

// Casts a node to its concrete class after checking its kind.
template <typename Node, typename Base> const Node& as(const Base& node) {
  return static_cast<const Node&>(node);
}
template <typename Node, typename Base> Node& as(Base& node) {
  return static_cast<Node&>(node);
}

} // namespace cncc::frontend
