// documented() (limits.h): the table docs/protocol.md is tested against, built
// from the same constants the reader checks with.
#include "study/protocol/limits.h"

#include <array>

namespace dtlab::protocol::limits {

namespace {

constexpr Documented ints(std::string_view section, std::string_view key, Ints r) {
  return {section, key, static_cast<double>(r.min), static_cast<double>(r.max)};
}
constexpr Documented numbers(std::string_view section, std::string_view key, Numbers r) {
  return {section, key, r.min, r.max};
}

constexpr std::array kDocumented{
    ints("top level", "format", kFormat),
    ints("top level", "participants", kParticipants),
    ints("top level", "master_seed", kMasterSeed),
    numbers("session", "time_limit_s", kSessionTimeLimit),
    numbers("training", "time_limit_s", kTrainingTimeLimit),
    ints("training", "practice_trials", kPracticeTrials),
    ints("breaks", "every_trials", kBreakEvery),
    numbers("breaks", "min_s", kBreakSeconds),
    numbers("breaks", "max_s", kBreakSeconds),
    ints("factors", "levels", kLevels),
    ints("order", "rows", kRandomRows),
    ints("order", "nested_rows", kRandomRows),
    ints("scenarios", "objects", kAbstractObjects),
    ints("scenarios", "objects", kWalkthroughObjects),
    numbers("scenarios", "extent", kExtent),
    numbers("scenarios", "object_radius", kObjectRadius),
    numbers("scenarios", "target_ratio", kTargetRatio),
    ints("scenarios", "letters", kLetters),
    ints("scenarios", "grid", kGrid),
    numbers("scenarios", "cell_size", kCellSize),
    ints("scenarios", "count_range", kCountRange),
    ints("tasks", "trials", kTrials),
    numbers("rendering", "a0", kAlpha),
    numbers("rendering", "aT", kAlpha),
    ints("rendering", "gradient_width", kGradientWidth),
    ints("rendering", "mask_resolution", kMaskResolution),
    ints("rendering", "layer_limit", kLayerLimit),
    numbers("rendering", "searchlight_radius", kSearchlightRadius),
    numbers("rendering", "radius", kLensSize),
    numbers("rendering", "distance", kLensSize),
    numbers("rendering", "length", kLensSize),
    ints("rendering", "screen_door_mask", kScreenDoorMask),
    numbers("rendering", "falloff", kVdtUnit),
    numbers("rendering", "opaque_alpha", kVdtUnit),
    numbers("rendering", "background_alpha", kVdtUnit),
    ints("questionnaire", "scale", kScale),
    ints("questionnaire", "options", kOptions),
    ints("questionnaire", "pairs", kPairs),
    ints("demographics", "range", kDemographicRange),
    ints("demographics", "options", kDemographicOptions),
    ints("reference_results", "participants", kReferenceParticipants),
    numbers("reference_results", "mean", kReferenceMean),
    numbers("reference_results", "sd", kReferenceSd),
};

}  // namespace

std::span<const Documented> documented() { return kDocumented; }

}  // namespace dtlab::protocol::limits
