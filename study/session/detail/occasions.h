// Internal: the runner's questionnaire occasions. Prepared before the session
// begins (every occasion of the plan and each depth-test item's view and key,
// so a questionnaire that cannot be shown stops the session before its first
// trial), then asked as the trials reach them: every occasion whose last
// trial is recorded and whose answers are not in the store is asked, in plan
// order, and stored in ONE Store::record_questionnaire transaction as soon as
// it is answered. What is answered is always read back from the store, so a
// resumed session asks exactly the occasions it had not stored.
// Never: keeps answers only in memory.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "study/session/session.h"

namespace dtlab::session::detail {

class Occasions {
 public:
  // The occasions of participant `index`'s plan and the depth-test views at viewport `vp`.
  static Result<Occasions> prepare(const protocol::Protocol& p, int index, const design::Plan& plan, const Viewport& vp);

  // Asks every occasion after a position <= `recorded` (the last recorded position; the plan's
  // last asks the end too) that the store does not hold yet; `history` is every trial recorded so
  // far. Returns how many occasions this call recorded.
  Result<int> ask_due(store::Store& store, const store::Session& session, const std::string& participant,
                      int enrollment_index, int recorded, const std::vector<RecordedTrial>& history, Responder& responder);

 private:
  struct DepthTest {
    DepthTestKey key;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> objects;  // per pair: Object::id of A and B
  };
  const protocol::Protocol* protocol_ = nullptr;
  std::vector<questionnaire::Occasion> occasions_;
  std::size_t next_ = 0;  // occasions before it are in the store (asked here, or found there)
  std::map<std::string, DepthTest> depth_tests_;  // by item id
};

}  // namespace dtlab::session::detail
