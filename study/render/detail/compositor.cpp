// The reference compositor (see compositor.h). Per pixel: collect surfaces
// and mask events, sort them far to near, fold them with the alpha rule.
#include <algorithm>
#include <cmath>
#include <limits>

#include "study/render/detail/compositor.h"

namespace dtlab::render::detail {

float gradient_alpha(float d, float alpha_start, float gradient_px) {
  if (gradient_px <= 0.0f) return 1.0f;
  return alpha_start + (1.0f - alpha_start) * std::clamp((d - 1.0f) / gradient_px, 0.0f, 1.0f);
}

std::vector<int> chessboard_distance(const std::vector<bool>& covered, int w, int h, int cap) {
  std::vector<int> d(static_cast<std::size_t>(w) * h, cap);
  auto at = [&](int x, int y) -> int& { return d[static_cast<std::size_t>(y) * w + x]; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (covered[static_cast<std::size_t>(y) * w + x]) at(x, y) = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int v = at(x, y);
      if (x > 0) v = std::min(v, at(x - 1, y) + 1);
      if (y > 0) {
        v = std::min(v, at(x, y - 1) + 1);
        if (x > 0) v = std::min(v, at(x - 1, y - 1) + 1);
        if (x + 1 < w) v = std::min(v, at(x + 1, y - 1) + 1);
      }
      at(x, y) = std::min(v, cap);
    }
  }
  for (int y = h - 1; y >= 0; --y) {
    for (int x = w - 1; x >= 0; --x) {
      int v = at(x, y);
      if (x + 1 < w) v = std::min(v, at(x + 1, y) + 1);
      if (y + 1 < h) {
        v = std::min(v, at(x, y + 1) + 1);
        if (x + 1 < w) v = std::min(v, at(x + 1, y + 1) + 1);
        if (x > 0) v = std::min(v, at(x - 1, y + 1) + 1);
      }
      at(x, y) = std::min(v, cap);
    }
  }
  return d;
}

namespace {

bool in_searchlight(const glm::vec3& s, int x, int y) {
  if (s.z < 0.0f) return true;
  const float dx = static_cast<float>(x) + 0.5f - s.x, dy = static_cast<float>(y) + 0.5f - s.y;
  return std::sqrt(dx * dx + dy * dy) <= s.z;
}

}  // namespace

MaskField exact_mask(const DtSettings& dt, glm::vec3 searchlight, const TargetView& t, const ObjectLayer* layer) {
  MaskField f;
  f.rect = t.support;
  const int w = f.rect.x1 - f.rect.x0, h = f.rect.y1 - f.rect.y0;
  if (w <= 0 || h <= 0) return f;
  const std::size_t n = static_cast<std::size_t>(w) * h;
  std::vector<bool> covered(n, false);
  std::vector<float> own(n, 2.0f);
  float nearest = 1.0f;  // the target's nearest depth
  for (int y = f.rect.y0; y < f.rect.y1; ++y) {
    for (int x = f.rect.x0; x < f.rect.x1; ++x) {
      const std::size_t k = static_cast<std::size_t>(y - f.rect.y0) * w + (x - f.rect.x0);
      if (layer != nullptr && layer->rect.overlaps({x, y, x + 1, y + 1})) {
        own[k] = layer->depth_at(x, y);
        if (own[k] < 1.0f) nearest = std::min(nearest, own[k]);
      }
      if (dt.shape == MaskShape::outline) {
        covered[k] = own[k] < 1.0f;
      } else {
        const glm::vec2 d = (glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f) - t.shape_center) /
                            glm::max(t.shape_radii, glm::vec2(1e-6f));
        covered[k] = glm::dot(d, d) <= 1.0f;
      }
    }
  }
  const int cap = static_cast<int>(std::ceil(dt.gradient_px)) + 2;
  const std::vector<int> dist = chessboard_distance(covered, w, h, cap);
  f.alpha.assign(n, 1.0f);
  f.depth.assign(n, nearest);
  for (int y = f.rect.y0; y < f.rect.y1; ++y) {
    for (int x = f.rect.x0; x < f.rect.x1; ++x) {
      const std::size_t k = static_cast<std::size_t>(y - f.rect.y0) * w + (x - f.rect.x0);
      if (!in_searchlight(searchlight, x, y)) continue;
      f.alpha[k] = covered[k] ? dt.alpha_target
                              : gradient_alpha(static_cast<float>(dist[k]), dt.alpha_start, dt.gradient_px);
      if (own[k] < 1.0f) f.depth[k] = own[k];
    }
  }
  return f;
}

namespace {

struct Event {
  float depth;
  int kind;        // 0: surface, 1: mask (surfaces sort before masks at equal depth)
  glm::vec4 color;  // surface colour
  float alpha;     // mask value
  bool target;     // surface of a target (R1 guard)
};

}  // namespace

CompositeOutput composite(const CompositeInput& in) {
  const int W = in.width, H = in.height;
  CompositeOutput out;
  out.rgba.assign(static_cast<std::size_t>(W) * H, glm::vec4(in.background, 1.0f));

  // The standard frame: frontmost surface per pixel (ties: the earlier object, as GL_LESS).
  std::vector<float> front_depth(out.rgba.size(), 1.0f);
  std::vector<int> front_layer(out.rgba.size(), -1);
  std::vector<int> layer_of_object;
  for (std::size_t li = 0; li < in.layers.size(); ++li) {
    const ObjectLayer& l = in.layers[li];
    if (l.object >= layer_of_object.size()) layer_of_object.resize(l.object + 1, -1);
    layer_of_object[l.object] = static_cast<int>(li);
    const int lw = l.rect.x1 - l.rect.x0;
    for (int y = l.rect.y0; y < l.rect.y1; ++y) {
      for (int x = l.rect.x0; x < l.rect.x1; ++x) {
        const std::size_t k = static_cast<std::size_t>(y - l.rect.y0) * lw + (x - l.rect.x0);
        const std::size_t p = static_cast<std::size_t>(y) * W + x;
        if (l.depth[k] < front_depth[p]) {
          front_depth[p] = l.depth[k];
          front_layer[p] = static_cast<int>(li);
        }
      }
    }
  }
  auto layer_index = [&](std::uint32_t object) {
    return object < layer_of_object.size() ? layer_of_object[object] : -1;
  };

  // Is any target hidden behind another object (inside the searchlight)?
  if (in.transparency) {
    for (const TargetView& t : in.targets) {
      const int li = layer_index(t.object);
      if (li < 0 || out.effect) continue;
      const ObjectLayer& l = in.layers[static_cast<std::size_t>(li)];
      for (int y = l.rect.y0; y < l.rect.y1 && !out.effect; ++y)
        for (int x = l.rect.x0; x < l.rect.x1 && !out.effect; ++x)
          if (l.depth_at(x, y) < 1.0f && front_layer[static_cast<std::size_t>(y) * W + x] != li &&
              in_searchlight(in.searchlight, x, y))
            out.effect = true;
    }
  }
  if (!out.effect) {
    for (std::size_t p = 0; p < out.rgba.size(); ++p) {
      if (front_layer[p] < 0) continue;
      const ObjectLayer& l = in.layers[static_cast<std::size_t>(front_layer[p])];
      const int x = static_cast<int>(p % W), y = static_cast<int>(p / W);
      const std::size_t k = static_cast<std::size_t>(y - l.rect.y0) * (l.rect.x1 - l.rect.x0) + (x - l.rect.x0);
      out.rgba[p] = glm::vec4(glm::vec3(l.color[k]), 1.0f);
    }
    return out;
  }

  std::vector<MaskField> masks;
  for (const TargetView& t : in.targets) {
    const int li = layer_index(t.object);
    masks.push_back(exact_mask(in.dt, in.searchlight, t, li < 0 ? nullptr : &in.layers[static_cast<std::size_t>(li)]));
  }
  const int limit = in.dt.layer_limit;
  std::vector<Event> events;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * W + x;
      // Impenetrable surfaces: z-buffered among themselves, drawn first, never transparent.
      float z_imp = 1.0f;
      glm::vec3 c = in.background;
      events.clear();
      for (const ObjectLayer& l : in.layers) {
        const bool is_target = l.object < in.is_target.size() && in.is_target[l.object];
        if (x < l.rect.x0 || x >= l.rect.x1 || y < l.rect.y0 || y >= l.rect.y1) continue;
        const std::size_t k = static_cast<std::size_t>(y - l.rect.y0) * (l.rect.x1 - l.rect.x0) + (x - l.rect.x0);
        const float z = l.depth[k];
        if (z >= 1.0f) continue;
        if (l.object < in.impenetrable.size() && in.impenetrable[l.object]) {
          if (z < z_imp) {
            z_imp = z;
            c = glm::vec3(l.color[k]);
          }
        } else {
          events.push_back({z, 0, l.color[k], 1.0f, is_target});
        }
      }
      for (const MaskField& m : masks) {
        if (x < m.rect.x0 || x >= m.rect.x1 || y < m.rect.y0 || y >= m.rect.y1) continue;
        const std::size_t k = static_cast<std::size_t>(y - m.rect.y0) * (m.rect.x1 - m.rect.x0) + (x - m.rect.x0);
        if (m.alpha[k] < 1.0f) events.push_back({m.depth[k], 1, glm::vec4(0.0f), m.alpha[k], false});
      }
      // Surfaces behind the impenetrable base fail the depth test; masks always apply.
      events.erase(std::remove_if(events.begin(), events.end(),
                                  [&](const Event& e) { return e.kind == 0 && !(e.depth < z_imp); }),
                   events.end());
      std::stable_sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
        if (a.depth != b.depth) return a.depth > b.depth;
        return a.kind < b.kind;
      });
      float alpha = 1.0f;
      int count = 0;  // the layer-limit counter (stencil low bits in the GPU methods)
      for (const Event& e : events) {
        if (e.kind == 1) {
          alpha *= e.alpha;
          count = 1;
          continue;
        }
        const glm::vec3 s(e.color);
        if (e.target && in.dt.r1_guard) alpha = std::max(alpha, in.dt.alpha_target);  // R1 guard
        if (limit > 0 && count >= limit + 1) {
          c = s;
          alpha = 1.0f;
          continue;
        }
        c = s * alpha + c * (1.0f - alpha);
        if (limit > 0) ++count;
      }
      out.rgba[p] = glm::vec4(c, alpha);
    }
  }
  return out;
}

}  // namespace dtlab::render::detail
