// A participant's trial plan as plain data: the ordered list of trials the
// session will run, derived only from (protocol, enrollment index, order row).
// Guarantee: the same inputs give the same plan on every machine; a plan never
// depends on what ran before. Numbers are derived from position (1-based).
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace dtlab::design {

struct PlannedTrial {
  int position = 0;  // 1-based position in the participant's session
  int block = 0;     // 1-based block number (a block = one ordered unit of the design: one
                     // condition's consecutive trials; a task set = a block's trials of one task)
  std::vector<std::pair<std::string, std::string>> levels;  // factor -> level, in protocol factor order
  std::string task;  // task id, e.g. "T1"
  int trial = 0;     // 1-based repetition of (condition, task)
  std::uint64_t seed = 0;  // trial seed (derivation documented in design/seeds.h)
  std::string method;      // rendering method, e.g. "standard", "dt-seed"
  bool practice = false;   // practice trials are run but not analysed
};

struct Plan {
  std::string protocol_id;
  int index = 0;      // 0-based enrollment index
  int order_row = 0;  // 0-based row of the ordering scheme
  std::vector<PlannedTrial> trials;
};

}  // namespace dtlab::design
