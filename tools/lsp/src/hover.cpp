// Hovers: what a name is. The declaration's kind and type; the value of a
// constant and the default of a parameter; a builtin's or function's
// signature and description; a curve's kind, degree, points and length.
// Elsewhere, what a set-up word does (setup_hover.cpp).
#include "cncc/lsp/features.h"
#include "cncc/lsp/protocol_json.h"
#include "curve_length.h"
#include "doc_comments.h"
#include "setup_hover.h"

#include <fmt/format.h>

namespace cncc::lsp {

namespace {

using frontend::Declaration;
using frontend::DeclarationKind;

std::string typeSuffix(const Declaration& declaration) {
  if (declaration.type.isLenient()) {
    return "";
  }
  return ": " + frontend::typeName(declaration.type);
}

// The line of code shown first, as the declaration would be written.
std::string codeLine(const Declaration& declaration) {
  switch (declaration.kind) {
  case DeclarationKind::Builtin:
  case DeclarationKind::Function:
    return (declaration.kind == DeclarationKind::Function ? "fn " : "") +
           (declaration.signature.empty() ? declaration.name : declaration.signature);
  case DeclarationKind::Constant:
    return "const " + declaration.name + typeSuffix(declaration);
  case DeclarationKind::Let:
    return "let " + declaration.name + typeSuffix(declaration);
  case DeclarationKind::LoopVariable:
    return "for " + declaration.name + typeSuffix(declaration);
  case DeclarationKind::Part:
    return "part " + declaration.name;
  case DeclarationKind::PartParameter:
  case DeclarationKind::FunctionParameter:
  case DeclarationKind::CurveParameter:
    return declaration.name + typeSuffix(declaration);
  }
  return declaration.name;
}

std::string curveDetails(const frontend::Value& value) {
  std::string text = frontend::describeValue(value);
  if (value.curve) {
    if (std::optional<double> length = curveLength(*value.curve)) {
      text += fmt::format(", length {:.6g}", *length);
    } else {
      text += ", length not computed (given by expressions in t)";
    }
  }
  return text;
}

// "value 3", "default 2.5", or a curve's description.
std::string valueLine(const Declaration& declaration) {
  if (!declaration.value || declaration.value->isError()) {
    return "";
  }
  const frontend::Value& value = *declaration.value;
  std::string described = value.type.kind == frontend::TypeKind::Curve
                              ? curveDetails(value)
                              : frontend::describeValue(value);
  switch (declaration.kind) {
  case DeclarationKind::PartParameter:
    return "default " + described;
  case DeclarationKind::Let:
    return "with the parameters at their defaults: " + described;
  default:
    return "value " + described;
  }
}

std::string description(const Analysis& analysis, const Declaration& declaration) {
  if (!declaration.description.empty()) {
    return declaration.description;
  }
  bool documented = declaration.kind == DeclarationKind::Function ||
                    declaration.kind == DeclarationKind::Constant ||
                    declaration.kind == DeclarationKind::Part;
  if (!documented || !declaration.span.valid()) {
    return "";
  }
  return docCommentAbove(analysis.sources().file(declaration.span.file).text(),
                         declaration.span.begin);
}

std::string where(const Analysis& analysis, const Declaration& declaration) {
  if (!declaration.span.valid() || declaration.span.file == analysis.file()) {
    return "";
  }
  return fmt::format(" in `{}`", analysis.sources().file(declaration.span.file).path());
}

std::string markdown(const Analysis& analysis, const Declaration& declaration) {
  std::string text = fmt::format("```cdl\n{}\n```\n", codeLine(declaration));
  text += fmt::format("*{}*{}", frontend::declarationKindName(declaration.kind),
                      where(analysis, declaration));
  if (std::string value = valueLine(declaration); !value.empty()) {
    text += " — " + value;
  }
  if (std::string about = description(analysis, declaration); !about.empty()) {
    text += "\n\n" + about;
  }
  return text;
}

} // namespace

Json hover(const Analysis& analysis, Position position) {
  std::uint32_t offset = analysis.offsetOf(position);
  const frontend::Reference* reference = analysis.program().referenceAt(analysis.file(), offset);
  if (reference == nullptr || reference->declaration == nullptr) {
    std::optional<SetupHover> setup = setupHover(analysis.module(), offset);
    if (!setup) {
      return nullptr;
    }
    return {{"contents", {{"kind", "markdown"}, {"value", setup->markdown}}},
            {"range", toJson(analysis.rangeOf(setup->span))}};
  }
  return {
      {"contents", {{"kind", "markdown"}, {"value", markdown(analysis, *reference->declaration)}}},
      {"range", toJson(analysis.rangeOf(reference->span))}};
}

} // namespace cncc::lsp
