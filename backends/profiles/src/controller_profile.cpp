#include "cncc/backends/controller_profile.h"

namespace cncc::backends {

namespace {

// Argument specification I, the same on Fanuc and Mitsubishi: G, L, N, O
// and P are not arguments.
std::vector<ArgumentLetter> specificationOneLetters() {
  return {{'A', 1},  {'B', 2},  {'C', 3},  {'I', 4},  {'J', 5},  {'K', 6},  {'D', 7},
          {'E', 8},  {'F', 9},  {'H', 11}, {'M', 13}, {'Q', 17}, {'R', 18}, {'S', 19},
          {'T', 20}, {'U', 21}, {'V', 22}, {'W', 23}, {'X', 24}, {'Y', 25}, {'Z', 26}};
}

ControllerProfile fanucProfile() {
  ControllerProfile profile;
  profile.name = "fanuc";
  profile.description = "Fanuc Custom Macro B, conservative 0i/16i/30i limits";
  profile.locals = {1, 33};
  profile.volatileCommon = {{100, 199}};
  profile.retainedCommon = {{500, 999}};
  profile.argumentLetters = specificationOneLetters();
  return profile;
}

ControllerProfile smallFanucProfile() {
  ControllerProfile profile = fanucProfile();
  profile.name = "fanuc-0i-small";
  profile.description = "Fanuc 0i with the small variable option (#100-#149, #500-#531)";
  profile.volatileCommon = {{100, 149}};
  profile.retainedCommon = {{500, 531}};
  return profile;
}

// Mitsubishi allows DO1..DO127 and 27 levels; the conservative profile keeps
// the Fanuc loop limits, which every M70/M80/M800 accepts.
ControllerProfile mitsubishiProfile() {
  ControllerProfile profile = fanucProfile();
  profile.name = "m80";
  profile.description = "Mitsubishi M70/M80/M800 macro program";
  profile.maximumProgramNumber = 99999999;
  profile.maximumSequenceNumber = 999999;
  profile.cornerArcOnMoveBlock = true;
  return profile;
}

const std::vector<ControllerProfile>& profileTable() {
  static const std::vector<ControllerProfile> profiles = {fanucProfile(), smallFanucProfile(),
                                                          mitsubishiProfile()};
  return profiles;
}

} // namespace

std::optional<char> ControllerProfile::letterForLocal(int variable) const {
  for (const ArgumentLetter& argument : argumentLetters) {
    if (argument.variable == variable) {
      return argument.letter;
    }
  }
  return std::nullopt;
}

std::optional<int> ControllerProfile::localForLetter(char letter) const {
  for (const ArgumentLetter& argument : argumentLetters) {
    if (argument.letter == letter) {
      return argument.variable;
    }
  }
  return std::nullopt;
}

int ControllerProfile::allocatableVariableCount() const {
  int count = locals.count();
  for (const VariableRange& range : volatileCommon) {
    count += range.count();
  }
  for (const VariableRange& range : retainedCommon) {
    count += range.count();
  }
  return count;
}

std::span<const ControllerProfile> builtinControllerProfiles() {
  return profileTable();
}

const ControllerProfile* findControllerProfile(std::string_view name) {
  for (const ControllerProfile& profile : profileTable()) {
    if (profile.name == name) {
      return &profile;
    }
  }
  return nullptr;
}

} // namespace cncc::backends
