// The pages of the session's sequence (detail/sequence.h), worded through the
// protocol's [text] table (study/protocol/wording.h).
#include "study/session/detail/sequence.h"

#include <cmath>
#include <cstdio>

#include "study/common/hash.h"
#include "study/protocol/wording.h"

namespace dtlab::session::detail {
namespace {

using protocol::text;

PageSpec page(const protocol::Protocol& p, PageSpec::Kind kind, std::string screen, std::string title,
              std::string body, std::string shown) {
  PageSpec s;
  s.kind = kind;
  s.protocol = &p;
  s.screen = std::move(screen);
  s.title = std::move(title);
  s.text = std::move(body);
  s.shown = std::move(shown);
  return s;
}

const design::PlannedTrial* first_of_block(const design::Plan& plan, int block) {
  for (const design::PlannedTrial& t : plan.trials)
    if (t.block == block) return &t;
  return nullptr;
}

std::string answer_text(const store::Answer& a) {
  if (const auto* c = std::get_if<store::Count>(&a)) return std::to_string(c->n);
  if (const auto* l = std::get_if<store::Letter>(&a)) return l->letter;
  return "";
}

}  // namespace

std::string block_levels_text(const protocol::Protocol& p, const design::PlannedTrial& t) {
  std::string s;
  for (const auto& [factor, level] : t.levels) s += (s.empty() ? "" : ", ") + protocol::level_text(p, factor, level);
  return s;
}

PageSpec consent_page(const protocol::Protocol& p) {
  const protocol::Consent& c = *p.flow.consent;
  return page(p, PageSpec::Kind::consent, "consent", c.title.empty() ? text(p, "consent.title") : c.title, c.text,
              sha256_hex(c.text));
}

std::vector<PageSpec> information_pages(const protocol::Protocol& p, protocol::Page::When when) {
  std::vector<PageSpec> out;
  for (const protocol::Page& pg : p.flow.pages)
    if (pg.when == when) out.push_back(page(p, PageSpec::Kind::information, "page " + pg.id, pg.title, pg.text, pg.id));
  return out;
}

std::vector<PageSpec> block_pages(const protocol::Protocol& p, const design::Plan& plan, int block) {
  std::vector<PageSpec> out;
  const design::PlannedTrial* first = first_of_block(plan, block);
  if (!first) return out;
  const int blocks = plan.trials.empty() ? 0 : plan.trials.back().block;
  const std::string next = block_levels_text(p, *first);
  if (block > 1 && p.flow.breaks.after_blocks) {
    PageSpec b = page(p, PageSpec::Kind::pause, "break", text(p, "break.title"),
                      text(p, "break.after_block", {{"done", std::to_string(block - 1)}, {"blocks", std::to_string(blocks)}}) +
                          "\n\n" + text(p, "break.next", {{"next", next}}),
                      "after block " + std::to_string(block - 1));
    b.min_s = p.flow.breaks.min_s;
    b.max_s = p.flow.breaks.max_s;
    b.skippable = p.flow.breaks.skippable;
    out.push_back(std::move(b));
  }
  if (p.flow.announce_blocks)
    out.push_back(page(p, PageSpec::Kind::announcement, "announce " + std::to_string(block), text(p, "announce.title"),
                       text(p, "announce.text",
                            {{"block", std::to_string(block)}, {"blocks", std::to_string(blocks)}, {"next", next}}),
                       next));
  // The instructions of each level met here for the first time in the plan.
  for (const auto& [factor, level] : first->levels) {
    const protocol::Factor* f = protocol::find_factor(p, factor);
    if (!f) continue;
    for (std::size_t i = 0; i < f->levels.size(); ++i) {
      if (f->levels[i] != level || f->instructions[i].empty()) continue;
      int first_block = 0;
      for (const design::PlannedTrial& t : plan.trials) {
        for (const auto& [tf, tl] : t.levels)
          if (tf == factor && tl == level) first_block = t.block;
        if (first_block) break;
      }
      if (first_block != block) continue;
      out.push_back(page(p, PageSpec::Kind::level_instructions, "level " + factor + "=" + level,
                         text(p, "level.title", {{"level", protocol::level_label(*f, static_cast<int>(i))}}),
                         f->instructions[i], factor + "=" + level));
    }
  }
  return out;
}

std::optional<PageSpec> trial_break(const protocol::Protocol& p, const design::Plan& plan,
                                    const design::PlannedTrial& last, const design::PlannedTrial& next) {
  const int every = p.flow.breaks.every_trials;
  if (every <= 0 || next.block != last.block) return std::nullopt;
  const design::PlannedTrial* first = first_of_block(plan, last.block);
  const int done = last.position - (first ? first->position : last.position) + 1;
  if (done % every != 0) return std::nullopt;
  const std::string what = block_levels_text(p, next);  // task ids are the protocol's, not the participant's words
  PageSpec b = page(p, PageSpec::Kind::pause, "break", text(p, "break.title"),
                    text(p, "break.inside_block") + "\n\n" + text(p, "break.next", {{"next", what}}),
                    "after trial " + std::to_string(last.position));
  b.min_s = p.flow.breaks.min_s;
  b.max_s = p.flow.breaks.max_s;
  b.skippable = p.flow.breaks.skippable;
  return b;
}

PageSpec feedback_page(const protocol::Protocol& p, const design::PlannedTrial& t, const store::Answer& truth,
                       const std::optional<store::Answer>& given) {
  std::string body;
  if (!given) {
    body = text(p, "feedback.none", {{"truth", std::holds_alternative<store::Position>(truth)
                                                   ? text(p, "feedback.position_truth")
                                                   : answer_text(truth)}});
  } else if (const auto* at = std::get_if<store::Position>(&*given)) {
    const auto& tp = std::get<store::Position>(truth);
    char d[32];
    std::snprintf(d, sizeof d, "%.1f", std::hypot(at->x - tp.x, at->z - tp.z));
    body = text(p, "feedback.position", {{"distance", d}});
  } else {
    body = text(p, std::holds_alternative<store::Letter>(truth) ? "feedback.letter" : "feedback.count",
                {{"truth", answer_text(truth)}, {"given", answer_text(*given)}});
  }
  return page(p, PageSpec::Kind::feedback, "feedback " + t.task, text(p, "feedback.title"), body,
              "trial " + std::to_string(t.position));
}

}  // namespace dtlab::session::detail
