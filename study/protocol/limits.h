// The range of every number a protocol may hold, in one table: the reader
// checks each value against these constants and nothing else, and
// tests/protocol/test_ranges.cpp checks that docs/protocol.md states exactly
// these ranges and that the ends of each one pass the whole validation.
// The questionnaire's keys are declared by their item types (study/questionnaire).
// The rendering methods' keys are declared by their key groups (study/technique).
// Guarantees: field-level only (one key at a time); constraints between keys
// (object radius against the cube, target ratio against objects, pairs
// against objects) belong to the stages that impose them and are checked by
// session::validate_runnable. Never: a range written anywhere else in code (the
// questionnaire's and the rendering methods' keys: only in their declarations).
#pragma once
#include <cstdint>
#include <limits>
#include <span>
#include <string_view>

namespace dtlab::protocol::limits {

struct Ints {  // closed interval of integers
  std::int64_t min;
  std::int64_t max;
};
struct Numbers {  // closed interval of finite numbers
  double min;
  double max;
};

// Top level.
inline constexpr Ints kFormat{1, 1};
inline constexpr Ints kParticipants{1, 100000};
inline constexpr Ints kMasterSeed{0, std::numeric_limits<std::int64_t>::max()};
// [session], [training].
inline constexpr Numbers kSessionTimeLimit{1, 86400};
inline constexpr Numbers kTrainingTimeLimit{0, 7200};
inline constexpr Ints kPracticeTrials{0, 100};
// [breaks].
inline constexpr Ints kBreakEvery{0, 1000};       // every_trials
inline constexpr Numbers kBreakSeconds{0, 7200};  // min_s, max_s
// [factors.*], [order].
inline constexpr Ints kFactors{1, 8};
inline constexpr Ints kLevels{2, 64};
inline constexpr Ints kConditions{1, 256};
inline constexpr Ints kRandomRows{1, 100000};       // rows, nested_rows
inline constexpr Ints kOrderRows{1, 100000};        // outer x nested rows of the whole ordering
inline constexpr Ints kPermutationItems{1, 8};      // full-permutation: 8! = 40320 rows
inline constexpr Ints kTrialsPerParticipant{1, 10000};
// [scenarios.*] and their tasks.
inline constexpr Ints kAbstractObjects{1, 2000};
inline constexpr Ints kWalkthroughObjects{1, 250};
inline constexpr Numbers kExtent{1, 100000};
inline constexpr Numbers kObjectRadius{0.01, 40000};  // and 2 max < extent
inline constexpr Numbers kTargetRatio{0.001, 1};
inline constexpr Ints kGrid{2, 32};
inline constexpr Numbers kCellSize{2, 999};
inline constexpr Ints kCountRange{1, 250};
inline constexpr Ints kLetters{1, 5};               // how many of C K R X Y
inline constexpr Ints kObjectKinds{1, 8};           // entries of object_kinds
inline constexpr Ints kTrials{1, 100};
// [rendering.*]: each method's key group declares its keys' ranges (study/technique, KeySpec);
// documented() lists them with these.
// [questionnaire.*]: each item type declares its keys' ranges (study/questionnaire, KeySpec);
// documented() lists them with these.
// [demographics.*].
inline constexpr Ints kDemographicRange{0, 1000000};  // an integer field's accepted values
inline constexpr Ints kDemographicOptions{2, 64};     // entries of a choice field's options
// [reference_results].
inline constexpr Ints kReferenceParticipants{1, 100000};
inline constexpr Numbers kReferenceMean{-1e9, 1e9};
inline constexpr Numbers kReferenceSd{0, 1e9};

// One documented range: the section of docs/protocol.md, the key as its table writes it, and
// the closed interval (integers up to 2^53 are exact in a double; master_seed's 2^63-1 is rounded).
struct Documented {
  std::string_view section;  // "top level", "session", "training", "breaks", "factors", "order", "scenarios",
                             // "tasks", "rendering", "questionnaire",
                             // "demographics", "reference_results"
  std::string_view key;      // as the table's first column writes it, e.g. "objects"
  double min;
  double max;
};

// Every numeric range of docs/protocol.md, in its order (the questionnaire's from the item types).
std::span<const Documented> documented();

}  // namespace dtlab::protocol::limits
