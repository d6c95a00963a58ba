// The start and end screens (start.h).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>

#include "app/run/screens.h"
#include "app/run/start.h"
#include "study/design/design.h"
#include "study/protocol/wording.h"
#include "study/store/read.h"

namespace dtlab::run {

namespace {

struct RowCount {
  int enrolled = 0, finished = 0, running = 0, abandoned = 0;
};

// What the start screen shows, read from the store (refreshed every second).
struct Progress {
  std::vector<RowCount> rows;
  std::vector<std::string> running;             // participants with a running session
  std::map<std::string, std::string> status;    // participant -> "finished", "running", "abandoned", "enrolled", "released"
  Clock::time_point read_at{};
};

Status read_progress(store::Store& store, int order_rows, Progress& out) {
  auto ledger = store.read().ledger();
  if (!ledger) return ledger.error();
  auto sessions = store.read().sessions();
  if (!sessions) return sessions.error();
  out = Progress{};
  out.rows.resize(static_cast<std::size_t>(std::max(1, order_rows)));
  std::map<std::string, const store::SessionRecord*> by_id;
  for (const auto& s : *sessions) by_id[s.participant] = &s;
  for (const auto& e : *ledger) {
    if (e.order_row >= static_cast<int>(out.rows.size())) out.rows.resize(static_cast<std::size_t>(e.order_row) + 1);
    RowCount& r = out.rows[static_cast<std::size_t>(e.order_row)];
    ++r.enrolled;
    std::string st = e.released_at ? "released" : "enrolled";
    if (auto it = by_id.find(e.participant); it != by_id.end()) {
      st = store::to_string(it->second->status);
      if (it->second->status == store::SessionStatus::finished) ++r.finished;
      if (it->second->status == store::SessionStatus::running) {
        ++r.running;
        out.running.push_back(e.participant);
      }
      if (it->second->status == store::SessionStatus::abandoned) ++r.abandoned;
    }
    out.status[e.participant] = st;
  }
  out.read_at = Clock::now();
  return {};
}

std::string design_text(const protocol::Protocol& p) {
  std::string s;
  for (const auto& f : p.factors) {
    s += (s.empty() ? "" : " x ") + f.name + " {";
    for (std::size_t i = 0; i < f.levels.size(); ++i) s += (i ? ", " : "") + protocol::level_label(f, static_cast<int>(i));
    s += "}";
  }
  const std::size_t trials = design::make_plan(p, 0).trials.size();
  return s + "; " + protocol::text(p, "start.design",
                                   {{"conditions", std::to_string(p.conditions.size())},
                                    {"scheme", std::string(protocol::to_string(p.order.scheme))},
                                    {"rows", std::to_string(protocol::declared_order_rows(p))},
                                    {"trials", std::to_string(trials)},
                                    {"participants", std::to_string(p.participants)}});
}

}  // namespace

Result<std::optional<StartChoice>> start_screen(Ui& ui, store::Store& store, const protocol::Protocol& p,
                                                const std::string& preset) {
  Progress progress;
  const int order_rows = protocol::declared_order_rows(p);
  if (Status s = read_progress(store, order_rows, progress); !s) return s.error();
  char id[store::kMaxParticipantId * 4 + 1] = {};  // room for more than the store keeps: too long is refused, never cut
  std::snprintf(id, sizeof id, "%s", preset.c_str());
  std::map<std::string, std::array<char, 128>> demo;
  for (const auto& f : p.demographics) demo[f.id] = {};
  std::string message, confirm_release;
  std::optional<std::optional<StartChoice>> result;
  const std::string design = design_text(p);

  while (!result) {
    if (Clock::now() - progress.read_at > std::chrono::seconds(1))
      if (Status s = read_progress(store, order_rows, progress); !s) return s.error();
    Status st = ui.frame("start", {}, [&] {
      const ImGuiIO& io = ImGui::GetIO();
      ImGui::SetNextWindowPos(ImVec2(0, 0));
      ImGui::SetNextWindowSize(io.DisplaySize);
      ImGui::Begin("##start", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove);
      ImGui::PushFont(ui.small_font());
      ImGui::PushFont(ui.heading_font());
      ImGui::TextWrapped("%s", p.title.c_str());
      ImGui::PopFont();
      ImGui::TextDisabled("Protocol %s (SHA-256 %.12s...), database %s", p.id.c_str(), p.sha256.c_str(),
                          store.path().c_str());
      // Two columns: the study on the left, the participant on the right (fits a small window).
      ImGui::BeginTable("layout", 2, ImGuiTableFlags_SizingStretchSame);
      ImGui::TableNextColumn();
      ImGui::TextWrapped("%s", design.c_str());
      if (ImGui::BeginTable("progress", 5, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit)) {
        for (const char* key : {"start.order_row", "start.enrolled", "start.finished_count", "start.running_count",
                                "start.abandoned_count"})
          ImGui::TableSetupColumn(protocol::text(p, key).c_str());
        ImGui::TableHeadersRow();
        for (std::size_t r = 0; r < progress.rows.size(); ++r) {
          const RowCount& c = progress.rows[r];
          ImGui::TableNextRow();
          for (int v : {static_cast<int>(r), c.enrolled, c.finished, c.running, c.abandoned}) {
            ImGui::TableNextColumn();
            ImGui::Text("%d", v);
          }
        }
        ImGui::EndTable();
      }
      ImGui::TableNextColumn();
      ImGui::PushFont(ui.heading_font());
      ImGui::TextUnformatted(protocol::text(p, "start.participant").c_str());
      ImGui::PopFont();
      const float field = ImGui::GetContentRegionAvail().x * 0.55f;
      ImGui::SetNextItemWidth(field);
      // The field keeps its script name "Participant ID" whatever the label reads.
      ImGui::InputText((protocol::text(p, "start.id") + "##participant").c_str(), id, sizeof id);
      ui.name_item("Participant ID");
      for (const auto& f : p.demographics) {
        auto& buf = demo[f.id];
        ImGui::SetNextItemWidth(field);
        const std::string label = f.prompt + (f.required ? " *" : "") + "##" + f.id;
        if (f.type == protocol::DemographicField::Type::choice) {
          const std::string choose = protocol::text(p, "start.choose");
          const char* shown = buf[0] ? buf.data() : choose.c_str();
          const bool open = ImGui::BeginCombo(label.c_str(), shown);
          ui.name_item(f.id);
          if (open) {
            for (const auto& o : f.options) {
              if (ImGui::Selectable(o.c_str(), o == buf.data())) std::snprintf(buf.data(), buf.size(), "%s", o.c_str());
              ui.name_item(f.id + ": " + o);
            }
            ImGui::EndCombo();
          }
        } else {
          ImGui::InputText(label.c_str(), buf.data(), buf.size(),
                           f.type == protocol::DemographicField::Type::integer ? ImGuiInputTextFlags_CharsDecimal : 0);
          ui.name_item(f.id);
        }
      }
      if (ui.button(protocol::text(p, "start.start"))) {
        const std::string who = id;
        const auto it = progress.status.find(who);
        if (who.empty()) {
          message = protocol::text(p, "start.type_id");
        } else if (Status ok = store::check_participant_id(who); !ok) {
          message = ok.error().message + ".";
        } else if (it != progress.status.end() && it->second == "finished") {
          message = protocol::text(p, "start.finished", {{"id", who}});
        } else if (it != progress.status.end() && (it->second == "released" || it->second == "abandoned")) {
          message = protocol::text(p, "start.released", {{"id", who}});
        } else if (it != progress.status.end()) {
          result = std::optional<StartChoice>(StartChoice{who, {}});  // enrolled or running: (re)start
        } else {
          std::vector<std::pair<std::string, std::string>> values;
          for (const auto& f : p.demographics) values.emplace_back(f.id, std::string(demo[f.id].data()));
          std::erase_if(values, [](const auto& v) { return v.second.empty(); });
          if (Status ok = protocol::check_demographics(p, values); !ok) {
            message = ok.error().to_string();
          } else if (p.flow.consent) {
            result = std::optional<StartChoice>(StartChoice{who, values});  // stored once consent is given
          } else if (auto e = store.enroll(who, values); !e) {
            message = e.error().to_string();
          } else {
            result = std::optional<StartChoice>(StartChoice{who, values});
          }
        }
      }
      if (!message.empty()) {
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextColored(ImVec4(0.75f, 0.1f, 0.1f, 1), "%s", message.c_str());
        ImGui::PopTextWrapPos();
      }
      if (!progress.running.empty()) {
        ImGui::Separator();
        ImGui::TextUnformatted(protocol::text(p, "start.running").c_str());
        for (const std::string& r : progress.running) {
          ImGui::PushID(r.c_str());
          if (ui.button(protocol::text(p, "start.resume", {{"id", r}}))) result = std::optional<StartChoice>(StartChoice{r, {}});
          ImGui::SameLine();
          if (confirm_release == r) {
            if (ui.button(protocol::text(p, "start.really_release", {{"id", r}}))) {
              Status rel = store.release(r);
              message = rel ? protocol::text(p, "start.released_now", {{"id", r}})
                            : rel.error().to_string();
              confirm_release.clear();
              progress.read_at = {};
            }
          } else if (ui.button(protocol::text(p, "start.release", {{"id", r}}))) {
            confirm_release = r;
          }
          ImGui::PopID();
        }
      }
      ImGui::Separator();
      if (ui.button(protocol::text(p, "start.quit"))) result = std::optional<StartChoice>();
      ImGui::EndTable();
      ImGui::PopFont();
      ImGui::End();
    });
    if (!st) return st.error();
    // A scripted run whose start section has played out while the screen refuses it (a finished
    // or released participant, a missing field): no step is left to change that, so say why
    // instead of waiting for a person who is not there.
    if (!result && !message.empty() && ui.script_played_out())
      return Error{ui.script()->file, ui.script_section_line(), 0, "start",
                   "the start screen refused the script's entries: " + message, ErrorKind::invalid_input};
  }
  return *result;
}

Status end_screen(Ui& ui, const std::string& screen, const std::string& title, const std::string& text,
                  const std::string& close) {
  for (bool done = false; !done;) {
    Status st = ui.frame(screen, {}, [&] {
      done = message_panel(ui, title, text, close) || ui.input().key_pressed(GLFW_KEY_ESCAPE);
    });
    if (!st) return st;
  }
  return {};
}

}  // namespace dtlab::run
