// Internal: the article's rendering order (section V.2). Objects form groups
// (Object::group 0 = a group of its own; objects sharing a non-zero group are
// one group, drawn together in order_in_group order, innermost first). Groups
// are sorted back to front by the signed distance of their centre (centre of
// the group's world bounding box, computed once) along the view vector, with
// a bubble sort that starts from the previous frame's order, so a frame with
// a camera that moved a little costs about one pass (frame coherence).
// Impenetrable objects are not sorted: the renderer draws them first.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "study/render/detail/scene_gpu.h"

namespace dtlab::render::detail {

class GroupSorter {
 public:
  explicit GroupSorter(const std::vector<ObjectRecord>& objects);
  // Non-impenetrable object indices, back to front by group, then by order_in_group.
  const std::vector<std::uint32_t>& sort(glm::vec3 eye, glm::vec3 forward);
  int last_swaps() const { return swaps_; }  // swaps the last sort() made (0: order was still valid)

 private:
  struct Group {
    std::vector<std::uint32_t> members;  // object indices in order_in_group order
    glm::vec3 center{0.0f};
  };
  std::vector<Group> groups_;
  std::vector<std::uint32_t> order_;    // group indices, back to front as of the last sort
  std::vector<std::uint32_t> objects_;  // flattened result
  int swaps_ = 0;
};

}  // namespace dtlab::render::detail
