// The report's walked-path figures drawn by study/replay: the one bridge
// between the report (which never links rendering) and the replay stage,
// shared by `dtlab analyze` and `dtlab demo`.
#pragma once
#include "analysis/report/report.h"
#include "study/replay/replay.h"

namespace dtlab::app {

// A ReportOptions::path_figure that draws with replay::trials_path_svg.
inline report::PathFigureFn replay_path_figures() {
  return [](store::StudyReader& reader, const std::string& participant, const std::vector<int>& positions,
            const std::string& title) -> Result<report::PathDrawing> {
    auto f = replay::trials_path_svg(reader, participant, positions, title);
    if (!f) return f.error();
    return report::PathDrawing{std::move(f->svg), std::move(f->left_out)};
  };
}

}  // namespace dtlab::app
