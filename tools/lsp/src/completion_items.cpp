#include "completion_items.h"

#include "cncc/frontend/ast.h"
#include "cncc/frontend/sema.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <set>

namespace cncc::lsp {

using frontend::Declaration;
using frontend::DeclarationKind;

void ItemBuilder::add(std::string label, ItemKind kind, std::string detail,
                      std::string documentation) {
  Json item = {{"label", std::move(label)}, {"kind", static_cast<int>(kind)}};
  if (!detail.empty()) {
    item["detail"] = std::move(detail);
  }
  if (!documentation.empty()) {
    item["documentation"] = {{"kind", "markdown"}, {"value", std::move(documentation)}};
  }
  items_.push_back(std::move(item));
}

void ItemBuilder::addSnippet(std::string label, ItemKind kind, std::string snippet,
                             std::string plain, std::string detail, std::string documentation) {
  add(std::move(label), kind, std::move(detail), std::move(documentation));
  Json& item = items_.back();
  if (snippets_) {
    item["insertText"] = std::move(snippet);
    item["insertTextFormat"] = 2; // Snippet
  } else {
    item["insertText"] = std::move(plain);
    item["insertTextFormat"] = 1; // PlainText
  }
}

void ItemBuilder::addReplacement(std::string label, ItemKind kind, Range range, std::string text) {
  add(label, kind);
  items_.back()["textEdit"] = {
      {"range",
       {{"start", {{"line", range.start.line}, {"character", range.start.character}}},
        {"end", {{"line", range.end.line}, {"character", range.end.character}}}}},
      {"newText", std::move(text)}};
  items_.back()["filterText"] = std::move(label);
}

Json ItemBuilder::list() const {
  return {{"isIncomplete", false}, {"items", items_}};
}

namespace {

struct KeywordSnippet {
  const char* label;
  const char* snippet;
  const char* plain;
  const char* detail;
};

void addKeywords(ItemBuilder& items, std::initializer_list<KeywordSnippet> keywords) {
  for (const KeywordSnippet& keyword : keywords) {
    items.addSnippet(keyword.label, ItemKind::Keyword, keyword.snippet, keyword.plain,
                     keyword.detail);
  }
}

} // namespace

void addStatementKeywords(ItemBuilder& items) {
  addKeywords(
      items,
      {
          {"units", "units ${1|mm,inch|}", "units ", "units mm | inch"},
          {"tool", "tool ${1:1} diameter=${2:10}", "tool ",
           "tool N diameter=D [length=H] [radius=R] [spindle=S] [feed=F]"},
          {"feed", "feed ${1:300}", "feed ", "feed F"},
          {"spindle", "spindle ${1:3000}", "spindle ", "spindle S"},
          {"safe", "safe z=${1:5}", "safe z=", "safe z=Z: clearance height"},
          {"origin", "origin ${1|G54,G55,G56,G57,G58,G59|}", "origin ",
           "origin G54 .. G59 | G54.1 P<n>: work offset"},
          {"coolant", "coolant ${1|flood,mist,through,off|}", "coolant ",
           "coolant flood | mist | through | off"},
          {"let", "let ${1:name} = ${2:value}", "let ", "let name = expr"},
          {"curve", "curve ${1:curve}", "curve ", "curve <curve-expr> [modifiers]"},
          {"for", "for ${1:i} in ${2:0} .. ${3:n} {\n\t$0\n}", "for ", "for i in a .. b { ... }"},
          {"if", "if ${1:condition} {\n\t$0\n}", "if ", "if cond { ... } else { ... }"},
      });
}

void addItemKeywords(ItemBuilder& items) {
  addKeywords(items,
              {
                  {"part", "part ${1:name}(${2}) {\n\t$0\n}", "part ",
                   "part name(p = default, ...) { ... }"},
                  {"fn", "fn ${1:name}(${2:x}) = ${0}", "fn ", "fn name(a, b) = expr"},
                  {"const", "const ${1:name} = ${0}", "const ", "const name = expr"},
                  {"import", "import \"${1:std/curves}\"", "import ", "import \"std/curves\""},
              });
}

void addExpressionKeywords(ItemBuilder& items) {
  addKeywords(items,
              {
                  {"if", "if ${1:condition} then ${2:a} else ${3:b}", "if ", "if c then a else b"},
                  {"then", "then", "then", "if c then a else b"},
                  {"else", "else", "else", "if c then a else b"},
                  {"true", "true", "true", "bool"},
                  {"false", "false", "false", "bool"},
              });
}

namespace {

struct ModifierInfo {
  const char* name;
  const char* snippet;
  const char* description;
};

const std::vector<ModifierInfo>& modifierInfos() {
  static const std::vector<ModifierInfo> infos = {
      {"sweep", "sweep depth=${1:3} step=${2:1}",
       "passes at Z = -S, -2S, ... down to exactly -D (with depth= and step=)"},
      {"depth", "depth=${1:3}", "the depth of a sweep"},
      {"step", "step=${1:1}", "the depth of each pass of a sweep"},
      {"tolerance", "tolerance=${1:0.01}",
       "the largest distance allowed between the tool path and the true curve (default 0.01 mm)"},
      {"samples", "samples=${1:100}", "N equally spaced parameter values (overrides tolerance)"},
      {"spacing", "spacing=${1:0.5}", "points equally spaced by arc length E"},
      {"method", "method=${1|linear,aspline,bspline,cspline,nurbs|}",
       "how the controller interpolates: G01 chords, Sinumerik A/B/C splines, or G06.2 NURBS"},
      {"feed", "feed=${1:300}", "feed for this cut (default: the tool's)"},
      {"entry", "entry=${1|plunge,ramp|}", "straight plunge, or ramped descent along the curve"},
      {"arcs", "arcs=${1|true,false|}",
       "G02/G03 arcs fitted within the tolerance instead of G01 chords (also --arcs; every "
       "target but jit)"},
      {"side", "side=${1|center,left,right|}",
       "the tool's centre on the curve, or beside it at the tool's radius, left or right of the "
       "curve in the direction of travel"},
      {"comp", "comp=${1|host,controller|}",
       "with side=left|right: the compiler computes the exact offset path (host), or the "
       "controller's G41/G42 does"},
      {"lead", "lead=${1:5}",
       "with side=left|right: tangent arc lead-in and lead-out of radius R off the curve"},
  };
  return infos;
}

bool mentions(std::string_view written, std::string_view word) {
  for (std::size_t at = written.find(word); at != std::string_view::npos;
       at = written.find(word, at + 1)) {
    bool startsWord = at == 0 || written[at - 1] == ' ' || written[at - 1] == '\t';
    std::size_t end = at + word.size();
    bool endsWord = end == written.size() || written[end] == '=' || written[end] == ' ';
    if (startsWord && endsWord) {
      return true;
    }
  }
  return false;
}

} // namespace

void addModifiers(ItemBuilder& items, std::string_view written) {
  for (const std::string& name : frontend::cutModifierNames()) {
    if (mentions(written, name)) {
      continue;
    }
    auto info = std::find_if(modifierInfos().begin(), modifierInfos().end(),
                             [&](const ModifierInfo& candidate) { return candidate.name == name; });
    std::string snippet = info != modifierInfos().end() ? info->snippet : name + "=";
    std::string description = info != modifierInfos().end() ? info->description : "";
    std::string plain = name == "sweep" ? "sweep" : name + "=";
    items.addSnippet(name, ItemKind::Property, snippet, plain, "modifier", description);
  }
}

namespace {

const std::vector<ModifierInfo>& toolSettingInfos() {
  static const std::vector<ModifierInfo> infos = {
      {"diameter", "diameter=${1:10}", "the tool's diameter (required)"},
      {"length", "length=${1:1}",
       "tool length offset register: G43 H<length> (default: the tool number)"},
      {"radius", "radius=${1:1}",
       "tool radius offset register D<radius> for cutter compensation (default: the tool "
       "number)"},
      {"spindle", "spindle=${1:3000}", "spindle speed when the tool is loaded"},
      {"feed", "feed=${1:300}", "feed rate for the tool's cuts"},
  };
  return infos;
}

} // namespace

void addToolSettings(ItemBuilder& items, std::string_view written) {
  for (const ModifierInfo& setting : toolSettingInfos()) {
    if (!mentions(written, setting.name)) {
      items.addSnippet(setting.name, ItemKind::Property, setting.snippet,
                       std::string(setting.name) + "=", "tool setting", setting.description);
    }
  }
}

void addOriginOffsets(ItemBuilder& items) {
  for (int group = 54; group <= 59; ++group) {
    items.add(fmt::format("G{}", group), ItemKind::EnumMember,
              fmt::format("work offset {}", group - 53));
  }
  items.add("G54.1 P1", ItemKind::EnumMember, "extended work offset P1 .. P300");
}

void addCoolantModes(ItemBuilder& items) {
  items.add("flood", ItemKind::EnumMember, "M08: flood coolant");
  items.add("mist", ItemKind::EnumMember, "M07: mist coolant");
  items.add("through", ItemKind::EnumMember, "through-spindle coolant (machine-specific M code)");
  items.add("off", ItemKind::EnumMember, "M09: coolant off");
}

void addModifierChoices(ItemBuilder& items, std::string_view modifier) {
  static const std::map<std::string_view, std::vector<std::pair<const char*, const char*>>>
      choices = {
          {"method",
           {{"linear", "G01 chords"},
            {"aspline", "Sinumerik A spline (Akima)"},
            {"bspline", "Sinumerik B spline"},
            {"cspline", "Sinumerik C spline (cubic)"},
            {"nurbs", "Fanuc G06.2 NURBS"}}},
          {"entry", {{"plunge", "straight plunge"}, {"ramp", "ramped descent along the curve"}}},
          {"side",
           {{"center", "the tool's centre on the curve"},
            {"left", "beside the curve at the tool's radius, to its left"},
            {"right", "beside the curve at the tool's radius, to its right"}}},
          {"comp",
           {{"host", "the compiler computes the exact offset path"},
            {"controller", "the controller's cutter radius compensation (G41/G42)"}}},
      };
  auto found = choices.find(modifier);
  if (found == choices.end()) {
    return;
  }
  for (const auto& [name, description] : found->second) {
    items.add(name, ItemKind::EnumMember, description);
  }
}

namespace {

// `nurbs(order=${1:order}, points=${2:points})` for the builtins that take
// named arguments (their signature says `name=`), `sin(${1:x})` for the rest.
std::string builtinSnippet(const frontend::BuiltinInfo& builtin) {
  bool named = builtin.signature.find('=') != std::string::npos;
  std::vector<std::string> arguments;
  if (builtin.variadic) {
    arguments = {"${1:curve}", "${2:curve}"};
  }
  for (const frontend::BuiltinParameter& parameter : builtin.parameters) {
    // One of order= and degree= is needed: offer order=.
    bool wanted = parameter.required || parameter.name == "order";
    if (!wanted) {
      continue;
    }
    std::string placeholder = fmt::format("${{{}:{}}}", arguments.size() + 1, parameter.name);
    arguments.push_back(named ? parameter.name + "=" + placeholder : placeholder);
  }
  std::string joined;
  for (const std::string& argument : arguments) {
    joined += (joined.empty() ? "" : ", ") + argument;
  }
  return builtin.name + "(" + joined + ")";
}

std::string functionSnippet(const Declaration& declaration) {
  std::string text = declaration.name + "(";
  if (declaration.function != nullptr) {
    const frontend::NodeList<frontend::Parameter>& parameters = declaration.function->parameters;
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      text += fmt::format("{}${{{}:{}}}", i == 0 ? "" : ", ", i + 1, parameters[i].name);
    }
  }
  return text + ")";
}

ItemKind kindOf(const Declaration& declaration) {
  switch (declaration.kind) {
  case DeclarationKind::Function:
    return ItemKind::Function;
  case DeclarationKind::Constant:
    return ItemKind::Constant;
  case DeclarationKind::Builtin:
    return declaration.signature.find('(') == std::string::npos ? ItemKind::Constant
                                                                : ItemKind::Function;
  default:
    return ItemKind::Variable;
  }
}

std::string detailOf(const Declaration& declaration) {
  if (!declaration.signature.empty()) {
    return declaration.signature;
  }
  std::string detail = std::string(frontend::declarationKindName(declaration.kind));
  if (!declaration.type.isLenient()) {
    detail += ": " + frontend::typeName(declaration.type);
  }
  if (declaration.value && !declaration.value->isError()) {
    detail += " = " + frontend::describeValue(*declaration.value);
  }
  return detail;
}

void addBuiltins(ItemBuilder& items, std::set<std::string>& added) {
  for (const frontend::BuiltinInfo& builtin : frontend::builtinFunctions()) {
    items.addSnippet(builtin.name, ItemKind::Function, builtinSnippet(builtin), builtin.name,
                     builtin.signature, builtin.description);
    added.insert(builtin.name);
  }
}

// The names declared in this file and the files it imports directly, and
// those in scope at `offset`; inner scopes hide outer ones.
std::map<std::string, const Declaration*> namesInScope(const Analysis& analysis,
                                                       std::uint32_t offset) {
  std::set<std::uint32_t> files{analysis.file().index};
  for (const frontend::ItemPtr& item : analysis.module().items) {
    if (item->kind == frontend::ItemKind::Import) {
      files.insert(frontend::as<frontend::ImportItem>(*item).resolvedFile.index);
    }
  }
  std::map<std::string, const Declaration*> names;
  for (const Declaration& declaration : analysis.program().declarations) {
    bool fileLevel = declaration.kind == DeclarationKind::Constant ||
                     declaration.kind == DeclarationKind::Function;
    if (fileLevel && files.contains(declaration.span.file.index)) {
      names.emplace(declaration.name, &declaration);
    }
  }
  for (const Declaration* declaration : analysis.program().visibleAt(analysis.file(), offset)) {
    if (declaration->kind != DeclarationKind::Builtin &&
        declaration->kind != DeclarationKind::Part) {
      names[declaration->name] = declaration;
    }
  }
  return names;
}

} // namespace

void addNames(ItemBuilder& items, const Analysis& analysis, std::uint32_t offset) {
  std::set<std::string> added;
  addBuiltins(items, added);
  items.add("pi", ItemKind::Constant, "pi = 3.14159...", "the constant pi");
  for (const auto& [name, declaration] : namesInScope(analysis, offset)) {
    if (added.contains(name)) {
      continue;
    }
    ItemKind kind = kindOf(*declaration);
    if (kind == ItemKind::Function) {
      items.addSnippet(name, kind, functionSnippet(*declaration), name, detailOf(*declaration));
    } else {
      items.add(name, kind, detailOf(*declaration));
    }
  }
}

std::vector<std::string> stdlibModules(const std::string& stdlibDirectory) {
  namespace fs = std::filesystem;
  std::vector<std::string> modules;
  std::error_code error;
  fs::recursive_directory_iterator entries(stdlibDirectory, error);
  for (; !error && entries != fs::recursive_directory_iterator(); entries.increment(error)) {
    const fs::path& path = entries->path();
    if (entries->is_regular_file(error) && path.extension() == ".cdl") {
      fs::path relative = path.lexically_relative(stdlibDirectory);
      modules.push_back(relative.replace_extension().generic_string());
    }
  }
  std::sort(modules.begin(), modules.end());
  return modules;
}

} // namespace cncc::lsp
