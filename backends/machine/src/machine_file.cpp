#include "cncc/backends/machine_file.h"
#include "cncc/backends/target_info.h"

#include "machine_block.h"

// With exceptions, as the shared toml++ library is built: toml::parse_error
// is caught below and becomes a diagnostic.
#include <toml++/toml.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <span>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <map>
#include <sstream>
#include <system_error>

namespace cncc::backends {

namespace {

// Blocks on the targets without a controller profile: a conservative line
// length every controller accepts (LinuxCNC's reader takes 255 (?)).
constexpr int defaultMaximumBlockLength = 255;

struct SetupStringField {
  std::string_view key;
  std::string MachineSetup::*member;
  std::string_view placeholder; // the one it takes, or none
  bool required = false;
};

constexpr SetupStringField setupStringFields[] = {
    {"length_offset", &MachineSetup::lengthOffset, "length"},
    {"tool_edge", &MachineSetup::toolEdge, "length"},
    {"work_offset", &MachineSetup::workOffset, "code", true},
    {"extended_work_offset", &MachineSetup::extendedWorkOffset, "number"},
    {"coolant_flood", &MachineSetup::coolantFlood, ""},
    {"coolant_mist", &MachineSetup::coolantMist, ""},
    {"coolant_through", &MachineSetup::coolantThrough, ""},
    {"coolant_off", &MachineSetup::coolantOff, ""},
    {"contouring_on", &MachineSetup::contouringOn, "tolerance"},
    {"contouring_off", &MachineSetup::contouringOff, ""},
};

struct ProfileIntegerField {
  std::string_view key;
  int ControllerProfile::*member;
  std::int64_t minimum = 1;
  std::int64_t maximum = 0; // 0: the profile's loop identifiers
};

constexpr ProfileIntegerField profileIntegerFields[] = {
    {"maximum_block_length", &ControllerProfile::maximumBlockLength, 16, 1024},
    {"coordinate_decimals", &ControllerProfile::coordinateDecimals, 0, 6},
    {"maximum_program_number", &ControllerProfile::maximumProgramNumber, 1, 99999999},
    {"maximum_sequence_number", &ControllerProfile::maximumSequenceNumber, 1, 99999999},
    {"maximum_loop_nesting", &ControllerProfile::maximumLoopNesting, 1, 0},
};

std::string_view typeName(toml::node_type type) {
  switch (type) {
  case toml::node_type::table:
    return "a table";
  case toml::node_type::array:
    return "an array";
  case toml::node_type::string:
    return "a string";
  case toml::node_type::integer:
    return "an integer";
  case toml::node_type::floating_point:
    return "a number with a fraction";
  case toml::node_type::boolean:
    return "a boolean";
  default:
    return "a date or time";
  }
}

// The targets a machine file may name, for messages.
std::string machineTargetNames() {
  return targetNameList([](const TargetInfo& target) { return !target.machineSetup.empty(); });
}

// A target whose programs are printed for a controller profile.
bool isMacroTarget(std::string_view target) {
  const TargetInfo* info = findTargetInfo(target);
  return info != nullptr && !info->controllerProfile.empty();
}

class MachineReader {
public:
  explicit MachineReader(std::vector<MachineDiagnostic>& diagnostics) : diagnostics_(diagnostics) {}

  std::optional<MachineDescription> read(const toml::table& root) {
    std::size_t before = diagnostics_.size();
    checkKeys(root,
              {"name", "description", "target", "profile", "setup", "program", "limits",
               "radius_offsets"},
              "");
    MachineDescription machine;
    readString(root, "name", machine.name);
    readString(root, "description", machine.description);
    readTarget(root, machine);
    const TargetInfo* target = findTargetInfo(machine.target);
    machine.setup = builtinMachineSetup(target != nullptr ? target->machineSetup : "");
    readProfile(root, machine);
    int blockLength =
        machine.profile ? machine.profile->maximumBlockLength : defaultMaximumBlockLength;
    if (const toml::table* setup = tableAt(root, "setup")) {
      readSetup(*setup, machine.setup, blockLength);
    }
    if (const toml::table* program = tableAt(root, "program")) {
      readProgram(*program, machine);
    }
    if (const toml::table* limits = tableAt(root, "limits")) {
      checkKeys(*limits, {"maximum_feed", "maximum_spindle_speed"}, "limits");
      readPositive(*limits, "maximum_feed", machine.maximumFeed);
      readPositive(*limits, "maximum_spindle_speed", machine.maximumSpindleSpeed);
      if (machine.profile) { // the virtual controller checks them too
        machine.profile->maximumFeed = machine.maximumFeed;
        machine.profile->maximumSpindleSpeed = machine.maximumSpindleSpeed;
      }
    }
    if (const toml::table* offsets = tableAt(root, "radius_offsets")) {
      readRadiusOffsets(*offsets, machine.radiusOffsets);
    }
    if (machine.profile) {
      machine.profile->maximumExtendedWorkOffset =
          machine.setup.extendedWorkOffset.empty() ? 0 : machine.setup.maximumExtendedWorkOffset;
    }
    if (diagnostics_.size() != before) {
      return std::nullopt;
    }
    return machine;
  }

private:
  void report(const toml::source_region& at, std::string code, std::string message) {
    diagnostics_.push_back({static_cast<int>(at.begin.line), static_cast<int>(at.begin.column),
                            std::move(message), std::move(code)});
  }

  void checkKeys(const toml::table& table, std::initializer_list<std::string_view> known,
                 std::string_view tableName) {
    for (const auto& [key, node] : table) {
      if (std::find(known.begin(), known.end(), key.str()) != known.end()) {
        continue;
      }
      std::string known_list;
      for (std::string_view name : known) {
        known_list += fmt::format("{}{}", known_list.empty() ? "" : ", ", name);
      }
      std::string where = tableName.empty() ? "" : fmt::format(" in [{}]", tableName);
      report(key.source(), node.is_table() ? "machine-unknown-table" : "machine-unknown-key",
             fmt::format("unknown {} '{}'{}; expected one of: {}",
                         node.is_table() ? "table" : "key", key.str(), where, known_list));
    }
  }

  // The node of `key` if it has the type `T`, else a diagnostic.
  template <typename T>
  const T* typed(const toml::table& table, std::string_view key, std::string_view expected) {
    const toml::node* node = table.get(key);
    if (node == nullptr) {
      return nullptr;
    }
    if (const T* value = node->as<T>()) {
      return value;
    }
    report(node->source(), "machine-wrong-type",
           fmt::format("'{}' must be {}, not {}", key, expected, typeName(node->type())));
    return nullptr;
  }

  const toml::table* tableAt(const toml::table& root, std::string_view key) {
    return typed<toml::table>(root, key, "a table");
  }

  bool readString(const toml::table& table, std::string_view key, std::string& into) {
    const toml::value<std::string>* value = typed<toml::value<std::string>>(table, key, "a string");
    if (value != nullptr) {
      into = value->get();
    }
    return value != nullptr;
  }

  // An integer or a number with a fraction, as a double.
  const toml::node* number(const toml::table& table, std::string_view key, double& into) {
    const toml::node* node = table.get(key);
    if (node == nullptr) {
      return nullptr;
    }
    if (std::optional<double> value = node->value_exact<double>()) {
      into = *value;
    } else if (const toml::value<std::int64_t>* integer = node->as_integer()) {
      into = static_cast<double>(integer->get());
    } else {
      report(node->source(), "machine-wrong-type",
             fmt::format("'{}' must be a number, not {}", key, typeName(node->type())));
      return nullptr;
    }
    return node;
  }

  void readPositive(const toml::table& table, std::string_view key, double& into) {
    double value = 0;
    const toml::node* node = number(table, key, value);
    if (node == nullptr) {
      return;
    }
    if (!std::isfinite(value) || value <= 0) {
      report(node->source(), "machine-out-of-range",
             fmt::format("'{}' must be a positive number, not {}", key, value));
      return;
    }
    into = value;
  }

  // `[radius_offsets]`: register = radius, registers 1 .. 9999 (D1 ..).
  void readRadiusOffsets(const toml::table& table, std::map<int, double>& into) {
    // In the file's order (the table keeps its keys sorted).
    std::vector<std::pair<const toml::key*, const toml::node*>> entries;
    for (const auto& [key, node] : table) {
      entries.emplace_back(&key, &node);
    }
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
      return a.first->source().begin.line < b.first->source().begin.line;
    });
    for (const auto& [key, node] : entries) {
      std::string_view name = key->str();
      int registerNumber = 0;
      auto [end, problem] = std::from_chars(name.data(), name.data() + name.size(), registerNumber);
      if (problem != std::errc() || end != name.data() + name.size() || registerNumber < 1 ||
          registerNumber > maximumRadiusOffsetRegister) {
        report(key->source(), "machine-unknown-key",
               fmt::format("'{}' in [radius_offsets] is not a register from 1 to {}", name,
                           maximumRadiusOffsetRegister));
        continue;
      }
      double radius = 0;
      if (number(table, name, radius) == nullptr) {
        continue;
      }
      if (!std::isfinite(radius)) {
        report(node->source(), "machine-out-of-range",
               fmt::format("the radius of register {} must be a finite number", registerNumber));
        continue;
      }
      into[registerNumber] = radius;
    }
  }

  void readTarget(const toml::table& root, MachineDescription& machine) {
    const toml::node* node = root.get("target");
    if (node == nullptr) {
      diagnostics_.push_back(
          {1, 1,
           fmt::format("the machine file names no target; add target = \"...\" ({})",
                       machineTargetNames()),
           "machine-missing-key"});
      return;
    }
    if (!readString(root, "target", machine.target)) {
      return;
    }
    if (!isMachineTarget(machine.target)) {
      report(node->source(), "machine-unknown-target",
             fmt::format("unknown target '{}'; expected one of: {}", machine.target,
                         machineTargetNames()));
    }
  }

  void readProfile(const toml::table& root, MachineDescription& machine) {
    const toml::table* table = tableAt(root, "profile");
    if (!isMacroTarget(machine.target)) {
      if (table != nullptr) {
        report(table->source(), "machine-profile-not-applicable",
               fmt::format("target '{}' has no controller profile; [profile] is for fanuc and m80",
                           machine.target));
      }
      return;
    }
    if (table == nullptr) {
      if (root.get("profile") == nullptr) {
        report(root.get("target")->source(), "machine-missing-key",
               fmt::format("target '{}' needs a [profile] with extends = \"...\" (fanuc, "
                           "fanuc-0i-small or m80)",
                           machine.target));
      }
      return;
    }
    checkKeys(*table,
              {"extends", "maximum_block_length", "coordinate_decimals", "least_input_increment",
               "maximum_program_number", "maximum_sequence_number", "maximum_loop_nesting",
               "macro_word_abbreviations"},
              "profile");
    std::string extends;
    if (table->get("extends") == nullptr) {
      report(table->source(), "machine-missing-key",
             "[profile] needs extends = \"...\", the built-in profile it changes (fanuc, "
             "fanuc-0i-small or m80)");
      return;
    }
    if (!readString(*table, "extends", extends)) {
      return;
    }
    const ControllerProfile* base = findControllerProfile(extends);
    if (base == nullptr) {
      report(table->get("extends")->source(), "machine-unknown-profile",
             fmt::format("unknown controller profile '{}'; the built-in ones are fanuc, "
                         "fanuc-0i-small and m80",
                         extends));
      return;
    }
    machine.profile = *base;
    readProfileOverrides(*table, *machine.profile);
  }

  void readProfileOverrides(const toml::table& table, ControllerProfile& profile) {
    for (const ProfileIntegerField& field : profileIntegerFields) {
      const toml::value<std::int64_t>* value =
          typed<toml::value<std::int64_t>>(table, field.key, "an integer");
      if (value == nullptr) {
        continue;
      }
      std::int64_t maximum = field.maximum != 0 ? field.maximum : profile.maximumLoopIdentifier;
      if (value->get() < field.minimum || value->get() > maximum) {
        report(value->source(), "machine-out-of-range",
               fmt::format("'{}' must be from {} to {}, not {}", field.key, field.minimum, maximum,
                           value->get()));
        continue;
      }
      profile.*field.member = static_cast<int>(value->get());
    }
    if (const toml::value<bool>* on =
            typed<toml::value<bool>>(table, "macro_word_abbreviations", "a boolean")) {
      profile.macroWordAbbreviations = on->get();
    }
    double increment = 0;
    if (const toml::node* node = number(table, "least_input_increment", increment)) {
      if (!(increment > 0 && increment <= 1)) {
        report(node->source(), "machine-out-of-range",
               fmt::format("'least_input_increment' must be above 0 and at most 1 (mm), not {}",
                           increment));
      } else {
        profile.leastInputIncrement = increment;
      }
    }
  }

  // A block of the setup: its placeholders, then the block it prints.
  bool checkBlock(const toml::node& node, std::string_view text,
                  std::span<const std::string_view> placeholders, const MachineSetup& setup,
                  int blockLength) {
    std::optional<machine::BlockProblem> problem = machine::placeholderProblem(text, placeholders);
    if (!problem) {
      problem = machine::blockProblem(machine::withSampleValues(text), setup.dialect, blockLength);
    }
    if (problem) {
      report(node.source(), problem->code, problem->message);
    }
    return !problem;
  }

  void readSetup(const toml::table& table, MachineSetup& setup, int blockLength) {
    std::vector<std::string_view> known;
    for (const SetupStringField& field : setupStringFields) {
      known.push_back(field.key);
    }
    for (std::string_view key : {"maximum_extended_work_offset", "high_speed", "end_retract",
                                 "start", "tool_change", "end"}) {
      known.push_back(key);
    }
    checkSetupKeys(table, known);
    for (const SetupStringField& field : setupStringFields) {
      std::string text;
      if (!readString(table, field.key, text)) {
        continue;
      }
      if (field.required && text.empty()) {
        report(table.get(field.key)->source(), "machine-out-of-range",
               fmt::format("'{}' cannot be empty", field.key));
      } else if (checkBlock(*table.get(field.key), text,
                            std::span(&field.placeholder, field.placeholder.empty() ? 0 : 1), setup,
                            blockLength)) {
        setup.*field.member = text;
      }
    }
    readWhole(table, "maximum_extended_work_offset", 1, 9999, setup.maximumExtendedWorkOffset);
    readBlocks(table, {"end_retract", {}, ""}, setup, setup.endRetract, blockLength);
    std::string_view startPlaceholders[] = {"units", "blend"};
    std::size_t startCount = setup.dialect == "linuxcnc" ? 2 : 1; // {blend} is LinuxCNC's
    readBlocks(table, {"start", std::span(startPlaceholders, startCount), "units"}, setup,
               setup.start, blockLength);
    std::string_view tool[] = {"tool"};
    readBlocks(table, {"tool_change", tool, "tool"}, setup, setup.toolChange, blockLength);
    readBlocks(table, {"end", {}, ""}, setup, setup.end, blockLength);
    readHighSpeed(table, setup);
  }

  void checkSetupKeys(const toml::table& table, const std::vector<std::string_view>& known) {
    for (const auto& [key, node] : table) {
      if (std::find(known.begin(), known.end(), key.str()) == known.end()) {
        report(key.source(), node.is_table() ? "machine-unknown-table" : "machine-unknown-key",
               fmt::format("unknown {} '{}' in [setup]; expected one of: {}",
                           node.is_table() ? "table" : "key", key.str(), fmt::join(known, ", ")));
      }
    }
  }

  struct BlockListField {
    std::string_view key;
    std::span<const std::string_view> placeholders;
    std::string_view required; // a placeholder some block must have, or none
  };

  void readBlocks(const toml::table& table, BlockListField field, const MachineSetup& setup,
                  std::vector<std::string>& into, int blockLength) {
    const toml::array* blocks = typed<toml::array>(table, field.key, "an array of strings");
    if (blocks == nullptr) {
      return;
    }
    std::vector<std::string> texts;
    bool valid = true;
    for (const toml::node& block : *blocks) {
      const toml::value<std::string>* text = block.as_string();
      if (text == nullptr) {
        report(
            block.source(), "machine-wrong-type",
            fmt::format("'{}' holds strings (blocks), not {}", field.key, typeName(block.type())));
        valid = false;
      } else if (checkBlock(block, text->get(), field.placeholders, setup, blockLength)) {
        texts.push_back(text->get());
      } else {
        valid = false;
      }
    }
    std::string placeholder = fmt::format("{{{}}}", field.required);
    if (valid && !field.required.empty() &&
        std::none_of(texts.begin(), texts.end(), [&](const std::string& text) {
          return text.find(placeholder) != std::string::npos;
        })) {
      report(blocks->source(), "machine-missing-placeholder",
             fmt::format("'{}' must have a block with {} ({})", field.key, placeholder,
                         field.required == "units" ? "the program's units, G21/G20 or G71/G70"
                                                   : "the tool number"));
    }
    into = std::move(texts);
  }

  // [program]: line numbers and comments.
  void readProgram(const toml::table& table, MachineDescription& machine) {
    checkKeys(table,
              {"line_numbers", "line_number_start", "line_number_increment", "line_number_maximum",
               "comments", "comment_case"},
              "program");
    MachineSetup& setup = machine.setup;
    // The largest N the controller takes (rs274 stops at 99999 as Fanuc does).
    int largest = machine.profile                ? machine.profile->maximumSequenceNumber
                  : setup.dialect == "sinumerik" ? 99999999
                                                 : 99999;
    setup.lineNumbers.maximum = std::min(setup.lineNumbers.maximum, largest);
    if (const toml::value<bool>* on =
            typed<toml::value<bool>>(table, "line_numbers", "a boolean")) {
      setup.lineNumbers.enabled = on->get();
    }
    readWhole(table, "line_number_maximum", 1, largest, setup.lineNumbers.maximum);
    readWhole(table, "line_number_start", 1, setup.lineNumbers.maximum, setup.lineNumbers.start);
    readWhole(table, "line_number_increment", 1, 1000, setup.lineNumbers.increment);
    if (const toml::value<bool>* on = typed<toml::value<bool>>(table, "comments", "a boolean")) {
      setup.comments = on->get();
    }
    std::string commentCase;
    if (readString(table, "comment_case", commentCase)) {
      if (commentCase == "upper" || commentCase == "as-written") {
        setup.commentCase = commentCase == "upper" ? CommentCase::Upper : CommentCase::AsWritten;
      } else {
        report(
            table.get("comment_case")->source(), "machine-out-of-range",
            fmt::format("'comment_case' is \"upper\" or \"as-written\", not \"{}\"", commentCase));
      }
    }
  }

  void readWhole(const toml::table& table, std::string_view key, int minimum, int maximum,
                 int& into) {
    const toml::value<std::int64_t>* value =
        typed<toml::value<std::int64_t>>(table, key, "an integer");
    if (value == nullptr) {
      return;
    }
    if (value->get() < minimum || value->get() > maximum) {
      report(
          value->source(), "machine-out-of-range",
          fmt::format("'{}' must be from {} to {}, not {}", key, minimum, maximum, value->get()));
      return;
    }
    into = static_cast<int>(value->get());
  }

  // high_speed = false: the machine has no contouring mode, so neither block.
  void readHighSpeed(const toml::table& table, MachineSetup& setup) {
    const toml::value<bool>* highSpeed = typed<toml::value<bool>>(table, "high_speed", "a boolean");
    if (highSpeed == nullptr || highSpeed->get()) {
      return;
    }
    for (std::string_view key : {"contouring_on", "contouring_off"}) {
      const toml::node* node = table.get(key);
      if (node != nullptr && node->is_string() && !node->as_string()->get().empty()) {
        report(node->source(), "machine-conflict",
               fmt::format("'{}' is set but high_speed = false", key));
      }
    }
    setup.contouringOn.clear();
    setup.contouringOff.clear();
  }

  std::vector<MachineDiagnostic>& diagnostics_;
};

} // namespace

bool isMachineTarget(std::string_view target) {
  const TargetInfo* info = findTargetInfo(target);
  return info != nullptr && !info->machineSetup.empty();
}

std::optional<MachineDescription> readMachineText(std::string_view text,
                                                  const std::string& displayName,
                                                  std::vector<MachineDiagnostic>& diagnostics) {
  try {
    toml::table root = toml::parse(text, displayName);
    return MachineReader(diagnostics).read(root);
  } catch (const toml::parse_error& error) {
    diagnostics.push_back({static_cast<int>(error.source().begin.line),
                           static_cast<int>(error.source().begin.column),
                           std::string(error.description()), "machine-syntax"});
    return std::nullopt;
  } catch (const std::exception& error) {
    diagnostics.push_back({0, 0, fmt::format("cannot read the machine file: {}", error.what()),
                           "machine-file-not-readable"});
    return std::nullopt;
  }
}

std::optional<MachineDescription> readMachineFile(const std::string& path,
                                                  std::vector<MachineDiagnostic>& diagnostics) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    diagnostics.push_back({0, 0,
                           fmt::format("cannot read machine file '{}': {}", path,
                                       std::error_code(errno, std::generic_category()).message()),
                           "machine-file-not-readable"});
    return std::nullopt;
  }
  std::ostringstream text;
  text << file.rdbuf();
  return readMachineText(text.str(), path, diagnostics);
}

} // namespace cncc::backends
