#include "cncc/backends/tnc_profile.h"

#include <fmt/format.h>

namespace cncc::backends {

namespace {

TncProfile tnc640Profile() {
  TncProfile profile;
  profile.name = "tnc640";
  profile.description = "Heidenhain TNC 640 / TNC 620, Klartext with formula entry and QL";
  profile.work = {{tncLocalBase + 0, tncLocalBase + 489}, {1600, 1989}};
  profile.scratch = {tncLocalBase + 490, tncLocalBase + 499};
  return profile;
}

TncProfile itnc530Profile() {
  TncProfile profile;
  profile.name = "itnc530";
  profile.description = "Heidenhain iTNC 530 without local QL parameters";
  profile.work = {{1600, 1989}};
  profile.scratch = {1990, 1999};
  return profile;
}

const std::vector<TncProfile>& profileTable() {
  static const std::vector<TncProfile> profiles = {tnc640Profile(), itnc530Profile()};
  return profiles;
}

} // namespace

std::string tncParameterName(int encoded) {
  if (encoded >= tncRetainedBase) {
    return fmt::format("QR{}", encoded - tncRetainedBase);
  }
  if (encoded >= tncLocalBase) {
    return fmt::format("QL{}", encoded - tncLocalBase);
  }
  return fmt::format("Q{}", encoded);
}

std::span<const TncProfile> builtinTncProfiles() {
  return profileTable();
}

const TncProfile* findTncProfile(std::string_view name) {
  for (const TncProfile& profile : profileTable()) {
    if (profile.name == name) {
      return &profile;
    }
  }
  return nullptr;
}

} // namespace cncc::backends
