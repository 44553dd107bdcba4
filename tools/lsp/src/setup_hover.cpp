#include "setup_hover.h"

#include <fmt/format.h>

namespace cncc::lsp {

namespace {

using frontend::as;
using frontend::SourceSpan;
using frontend::StmtKind;

bool contains(SourceSpan span, std::uint32_t offset) {
  return span.begin <= offset && offset <= span.end;
}

std::string originMarkdown(const frontend::OriginStmt& origin) {
  std::string written = frontend::originOffsetSpelling(origin);
  if (origin.extended != 0) {
    written += fmt::format(" P{}", origin.extended);
  }
  return fmt::format("```cdl\norigin {}\n```\nThe work offset of the moves that follow, until the "
                     "next `origin`: `G54` .. `G59` are printed as they are, `G54.1 P1` .. `P300` "
                     "select the extended offsets. A part without one runs in `G54`.",
                     written);
}

std::string coolantMarkdown(const frontend::CoolantStmt& coolant) {
  return fmt::format("```cdl\ncoolant {}\n```\nCoolant from here to the next `coolant`: `flood` "
                     "is `M08`, `mist` `M07` and `off` `M09`; `through` (through the spindle) "
                     "has a machine-specific code.",
                     frontend::coolantModeSpelling(coolant.mode));
}

std::optional<SetupHover> settingHover(const frontend::ToolStmt& tool, std::uint32_t offset) {
  for (const frontend::Argument& setting : tool.settings) {
    if (!contains(setting.nameSpan, offset)) {
      continue;
    }
    if (setting.name == "length") {
      return SetupHover{"```cdl\nlength=H\n```\nThe tool length offset register: after the tool "
                        "change the program turns it on with `G43 H<length>` before moving in "
                        "Z. Defaults to the tool number.",
                        setting.nameSpan};
    }
    if (setting.name == "radius") {
      return SetupHover{"```cdl\nradius=R\n```\nThe tool radius offset register `D<radius>` "
                        "that the controller's cutter compensation (`comp=controller`) reads. "
                        "Defaults to the tool number.",
                        setting.nameSpan};
    }
  }
  return std::nullopt;
}

std::optional<SetupHover> blockHover(const frontend::Block& block, std::uint32_t offset);

std::optional<SetupHover> statementHover(const frontend::Stmt& statement, std::uint32_t offset) {
  switch (statement.kind) {
  case StmtKind::Origin:
    return SetupHover{originMarkdown(as<frontend::OriginStmt>(statement)), statement.span};
  case StmtKind::Coolant:
    return SetupHover{coolantMarkdown(as<frontend::CoolantStmt>(statement)), statement.span};
  case StmtKind::Tool:
    return settingHover(as<frontend::ToolStmt>(statement), offset);
  case StmtKind::For:
    return blockHover(as<frontend::ForStmt>(statement).body, offset);
  case StmtKind::If: {
    const auto& branch = as<frontend::IfStmt>(statement);
    std::optional<SetupHover> found = blockHover(branch.thenBlock, offset);
    return found ? found : blockHover(branch.elseBlock, offset);
  }
  default:
    return std::nullopt;
  }
}

std::optional<SetupHover> blockHover(const frontend::Block& block, std::uint32_t offset) {
  for (const frontend::StmtPtr& statement : block.statements) {
    if (contains(statement->span, offset)) {
      return statementHover(*statement, offset);
    }
  }
  return std::nullopt;
}

} // namespace

std::optional<SetupHover> setupHover(const frontend::Module& module, std::uint32_t offset) {
  for (const frontend::ItemPtr& item : module.items) {
    if (item->kind == frontend::ItemKind::Part && contains(item->span, offset)) {
      return blockHover(as<frontend::PartItem>(*item).body, offset);
    }
  }
  return std::nullopt;
}

} // namespace cncc::lsp
