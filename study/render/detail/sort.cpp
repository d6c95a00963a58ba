// Frame-coherent bubble sort of groups (see sort.h).
#include <algorithm>
#include <limits>
#include <map>
#include <utility>

#include "study/render/detail/sort.h"

namespace dtlab::render::detail {

GroupSorter::GroupSorter(const std::vector<ObjectRecord>& objects) {
  std::map<std::uint32_t, std::size_t> by_id;  // non-zero group id -> index in groups_
  for (std::uint32_t i = 0; i < objects.size(); ++i) {
    const ObjectRecord& o = objects[i];
    if (o.impenetrable) continue;
    if (o.group == 0) {
      groups_.push_back(Group{{i}, {}});
      continue;
    }
    auto [it, fresh] = by_id.emplace(o.group, groups_.size());
    if (fresh) groups_.push_back(Group{});
    groups_[it->second].members.push_back(i);
  }
  for (Group& g : groups_) {
    std::stable_sort(g.members.begin(), g.members.end(), [&](std::uint32_t a, std::uint32_t b) {
      return objects[a].order_in_group < objects[b].order_in_group;
    });
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (auto m : g.members) {
      lo = glm::min(lo, objects[m].world_min);
      hi = glm::max(hi, objects[m].world_max);
    }
    g.center = 0.5f * (lo + hi);
  }
  for (std::uint32_t i = 0; i < groups_.size(); ++i) order_.push_back(i);
}

const std::vector<std::uint32_t>& GroupSorter::sort(glm::vec3 eye, glm::vec3 forward) {
  std::vector<float> key(groups_.size());
  for (std::size_t g = 0; g < groups_.size(); ++g) key[g] = glm::dot(groups_[g].center - eye, forward);
  swaps_ = 0;
  // Bubble sort, farthest first; stops after the first pass without a swap.
  for (std::size_t end = order_.size(); end > 1; --end) {
    bool swapped = false;
    for (std::size_t i = 1; i < end; ++i) {
      if (key[order_[i - 1]] < key[order_[i]]) {
        std::swap(order_[i - 1], order_[i]);
        swapped = true;
        ++swaps_;
      }
    }
    if (!swapped) break;
  }
  objects_.clear();
  for (auto g : order_) objects_.insert(objects_.end(), groups_[g].members.begin(), groups_[g].members.end());
  return objects_;
}

}  // namespace dtlab::render::detail
