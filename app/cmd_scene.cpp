// `dtlab scene --scene abstract|walkthrough --task T1..T4 --seed S [--json]
// [--obj FILE]`: generates one trial scene with the reference study's
// parameters and prints its summary (objects by kind, targets, triangles,
// answer key, content hash); --obj writes the whole scene as Wavefront
// OBJ + MTL. Exit 1 when the task does not belong to the scene kind, 3 when
// the OBJ files cannot be written.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>

#include "app/commands.h"
#include "study/scene/generate.h"
#include "study/scene/obj.h"

namespace dtlab::app {

namespace {

struct SceneOptions {
  std::string kind, task, obj, seed_text;
  std::uint64_t seed = 0;  // parsed from seed_text by the --seed validator
  bool json = false;
};

double degrees(float radians) { return static_cast<double>(radians) * 180.0 / M_PI; }

// The start camera: what a lens's `distance` is measured along (an orbit's distance puts the lens on
// the orbit's centre), in the units `dtlab render --camera` takes (degrees).
nlohmann::ordered_json camera_json(const scene::CameraStart& c) {
  auto vec = [](glm::vec3 v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); };
  nlohmann::ordered_json j{{"mode", c.mode == scene::CameraStart::Mode::orbit ? "orbit" : "walk"}};
  if (c.mode == scene::CameraStart::Mode::orbit) {
    j["target"] = vec(c.target);
    j["distance"] = c.distance;
  } else {
    j["position"] = vec(c.position);
  }
  j["yaw_deg"] = degrees(c.yaw);
  j["pitch_deg"] = degrees(c.pitch);
  j["fov_y_deg"] = degrees(c.fov_y);
  j["near"] = c.near_plane;
  j["far"] = c.far_plane;
  return j;
}

std::string camera_text(const scene::CameraStart& c) {
  char buf[256];
  if (c.mode == scene::CameraStart::Mode::orbit)
    std::snprintf(buf, sizeof buf, "orbit around (%.3g, %.3g, %.3g) at distance %.4g, yaw %.1f deg, pitch %.1f deg, "
                  "field of view %.1f deg", c.target.x, c.target.y, c.target.z, c.distance, degrees(c.yaw),
                  degrees(c.pitch), degrees(c.fov_y));
  else
    std::snprintf(buf, sizeof buf, "walk from (%.3g, %.3g, %.3g), yaw %.1f deg, field of view %.1f deg",
                  c.position.x, c.position.y, c.position.z, degrees(c.yaw), degrees(c.fov_y));
  return buf;
}

nlohmann::ordered_json answer_json(const scene::Answer& a) {
  switch (a.task) {
    case scene::Task::T1: return {{"count", a.count}};
    case scene::Task::T2: return {{"letter", std::string(1, a.letter)}};
    case scene::Task::T3: return {{"kind", a.target_kind}, {"x", a.position.x}, {"z", a.position.y}};
    case scene::Task::T4: return {{"kind", a.target_kind}, {"count", a.count}};
  }
  return {};
}

std::string answer_text(const scene::Answer& a) {
  char buf[160];
  switch (a.task) {
    case scene::Task::T1: return "count " + std::to_string(a.count) + " (red objects)";
    case scene::Task::T2: return std::string("letter ") + a.letter + " (formed by the red cones)";
    case scene::Task::T3:
      std::snprintf(buf, sizeof buf, "the one %s, at x %.3f z %.3f", a.target_kind.c_str(),
                    static_cast<double>(a.position.x), static_cast<double>(a.position.y));
      return buf;
    case scene::Task::T4: return "count " + std::to_string(a.count) + " of kind " + a.target_kind;
  }
  return "";
}

void run(const SceneOptions& o) {
  const auto kind = *scene::parse_kind(o.kind);  // CLI11 checked the spelling
  const auto task = *scene::parse_task(o.task);
  const auto s = scene::generate(kind, task, o.seed);
  if (!s.ok()) {
    std::cerr << "dtlab scene: error: " << s.error().to_string() << "\n";
    throw CLI::RuntimeError(kExitInvalid);
  }
  std::map<std::string, int> by_kind;
  std::size_t triangles = 0;
  int targets = 0;
  for (const auto& obj : s->objects) {
    ++by_kind[obj.kind];
    triangles += s->meshes[obj.mesh].triangle_count();
    targets += obj.target;
  }
  if (!o.obj.empty()) {
    if (Status st = scene::save_obj(*s, o.obj); !st) {
      std::cerr << "dtlab scene: error: " << st.error().to_string() << "\n";
      throw CLI::RuntimeError(kExitFailure);
    }
  }
  if (o.json) {
    nlohmann::ordered_json objects = nlohmann::ordered_json::object();
    for (const auto& [k, n] : by_kind) objects[k] = n;
    const nlohmann::ordered_json j{{"scene", o.kind},     {"task", o.task},   {"seed", o.seed},
                                   {"hash", s->hash},     {"objects", objects}, {"targets", targets},
                                   {"triangles", triangles}, {"answer", answer_json(s->answer)},
                                   {"camera", camera_json(s->camera)}};
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::string kinds;
  for (const auto& [k, n] : by_kind) kinds += (kinds.empty() ? "" : ", ") + k + " " + std::to_string(n);
  std::cout << "scene      " << o.kind << " " << o.task << ", seed " << o.seed << "\n"
            << "hash       " << s->hash << "\n"
            << "objects    " << s->objects.size() << ": " << kinds << "\n"
            << "targets    " << targets << " (uncovered by dynamic transparency)\n"
            << "triangles  " << triangles << "\n"
            << "answer     " << answer_text(s->answer) << "\n"
            << "camera     " << camera_text(s->camera) << "\n";
  if (!o.obj.empty())
    std::cout << "obj        " << o.obj << " + " << std::filesystem::path(o.obj).replace_extension(".mtl").string()
              << "\n";
}

}  // namespace

void add_scene_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("scene", "Generate one trial scene from a seed; print its summary, export OBJ");
  auto o = std::make_shared<SceneOptions>();
  cmd->add_option("--scene", o->kind, "Scene kind: abstract (tasks T1, T2) or walkthrough (T3, T4)")
      ->required()
      ->check(CLI::IsMember({"abstract", "walkthrough"}));
  cmd->add_option("--task", o->task, "Task: T1 count red, T2 letter, T3 find the unique object, T4 count a kind")
      ->required()
      ->check(CLI::IsMember({"T1", "T2", "T3", "T4"}));
  // Parsed here, not by CLI11: its integer conversion saturates out-of-range values silently.
  const CLI::Validator uint64_only(
      [o](std::string& v) {
        const char* end = v.data() + v.size();
        const auto [ptr, ec] = std::from_chars(v.data(), end, o->seed);
        return !v.empty() && v[0] != '-' && v[0] != '+' && ec == std::errc() && ptr == end
                   ? std::string()
                   : "expected an unsigned integer 0 .. 18446744073709551615, got '" + v + "'";
      },
      "UINT64");
  cmd->add_option("--seed", o->seed_text, "Trial seed (unsigned 64-bit)")->required()->check(uint64_only);
  cmd->add_flag("--json", o->json,
                "Print {\"scene\", \"task\", \"seed\", \"hash\", \"objects\": {kind: count}, \"targets\", "
                "\"triangles\", \"answer\", \"camera\": {mode, target and distance (orbit) or position (walk), "
                "yaw_deg, pitch_deg, fov_y_deg, near, far}} as JSON");
  cmd->add_option("--obj", o->obj, "Also write the scene as Wavefront OBJ to FILE and its materials to FILE.mtl");
  cmd->footer(
      "Parameters are the reference study's (study/scene/generate.h); the hash is SHA-256 of the\n"
      "canonical serialization (docs/scene.md), the same on every machine.\n"
      "Exit status: 0 ok, 1 task not of this scene kind, 2 bad command line, 3 OBJ not written.");
  cmd->callback([o] { run(*o); });
}

}  // namespace dtlab::app
