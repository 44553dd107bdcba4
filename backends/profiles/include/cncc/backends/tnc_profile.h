// What a Heidenhain TNC accepts, as data: the printer of Heidenhain
// programs (backends/heidenhain) and the virtual TNC (backends/sim) read
// the same profile, so a program that does not fit is refused at compile
// time with the limit named. Facts from the TNC user's manuals (TARGETS.md,
// "Heidenhain TNC"); uncertain ones take the conservative value.
//
// Q parameters are numbered for the register allocator as one integer
// each: Q n is n, QL n is tncLocalBase + n, QR n is tncRetainedBase + n
// (tncParameterName spells them).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

inline constexpr int tncLocalBase = 10000;
inline constexpr int tncRetainedBase = 20000;

// Q parameters `first` to `last` of one kind, inclusive (encoded as above).
struct TncParameterRange {
  int first = 0;
  int last = -1;
  int count() const { return last >= first ? last - first + 1 : 0; }
};

struct TncProfile {
  std::string name;        // "tnc640", "itnc530"
  std::string description; // one line
  // The part parameters, set by FN 0 at the top where the operator edits
  // them: Q1-Q59 (Q0-Q99 are the user's; Q60-Q99 may belong to OEM cycles).
  TncParameterRange partParameters{1, 59};
  // Where computed values go, in the order preferred: QL (local to the
  // program) where the control has them, else the free Q1600-Q1999.
  std::vector<TncParameterRange> work;
  // Scratch parameters the printer writes just before the block that reads
  // them (an address or a jump takes a number or one parameter, never a
  // formula), the last one the tool's Z where a helix needs it; never
  // given to the allocator.
  TncParameterRange scratch;
  int maximumLabel = 999;       // LBL 1 .. LBL this (LBL 0 ends a subprogram)
  int maximumBlockLength = 255; // characters in one block, block number included
  int maximumBlockNumber = 99999;
  int coordinateDecimals = 4; // mm (0.1 um input resolution); inch: one more
  // Digits of a printed constant: the TNC takes 15, of which 9 before the
  // point; 12 keep blocks short and stay far below the input resolution.
  int significantDigits = 12;
  double maximumMagnitude = 999999999; // a Q parameter's value, +-
  int maximumCallNesting = 19;         // CALL LBL / CALL PGM depth
  // SPL blocks: the largest |K| coefficient.
  double maximumSplineCoefficient = 9.99999999;
};

// "Q5", "QL12", "QR3" for an encoded parameter.
std::string tncParameterName(int encoded);

// The built-in profiles: "tnc640" (QL0-QL499 for values), "itnc530"
// (older software without QL: Q1600-Q1999).
std::span<const TncProfile> builtinTncProfiles();
const TncProfile* findTncProfile(std::string_view name);

} // namespace cncc::backends
