// A generated trial world as plain data: meshes, objects, answer key, start
// camera. Scenes are values built from (kind, task, seed, parameters) by
// study/scene and drawn by study/render; nothing here knows about OpenGL.
// Guarantee: the same inputs give the same Scene, and the same `hash`, on
// every machine (no std::hash, no global RNG, no unordered iteration).
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace dtlab::scene {

enum class Kind { abstract, walkthrough };
enum class Task { T1, T2, T3, T4 };  // T1/T2 ABSTRACT, T3/T4 WALKTHROUGH (STUDY.md)

struct Vertex {
  glm::vec3 position;
  glm::vec3 normal;                // unit length
  glm::vec3 color{1.0f};           // linear RGB in [0,1], multiplied by Object::color
};

// Indexed triangle list in the mesh's own (model) space.
struct Mesh {
  std::string name;                // e.g. "sphere", "dog"
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;  // 3 per triangle, counter-clockwise front faces
  std::size_t triangle_count() const { return indices.size() / 3; }
};

struct Object {
  std::uint32_t id = 0;            // 1-based, unique in the scene; 0 is "no object" in ID buffers
  std::string kind;                // "sphere", "cone", "box", "torus", "dog", "wall", "floor", ...
  glm::vec3 color{1.0f};           // tint multiplied into the mesh's vertex colours
  glm::mat4 transform{1.0f};       // model -> world
  std::uint32_t mesh = 0;          // index into Scene::meshes
  bool target = false;             // uncovered by dynamic transparency: ABSTRACT every red object (T1 the
                                   // counted targets; T2 the letter cones and the red distractors);
                                   // WALKTHROUGH every model, never walls, floor or ceiling (docs/scene.md)
  bool impenetrable = false;       // never turns transparent (rule R3)
  std::uint32_t group = 0;         // sort group (objects of a group are drawn together); the generators
                                   // give every object its own group (group == id)
  std::uint32_t order_in_group = 0;  // fixed draw order inside the group, innermost first
};

// Walkthrough floor plan on a grid: the 2D map participants mark in T3.
struct FloorPlan {
  int width = 0, height = 0;       // cells (16 x 16 in the reference study)
  float cell_size = 0.0f;          // world units per cell
  std::vector<int> room;           // room id per cell, row-major (y * width + x)
  struct Door { int x0, y0, x1, y1; };  // a doorway between two edge-adjacent cells of different rooms
  std::vector<Door> doors;
};

// What a correct answer is. Exactly one member is meaningful per task:
// T1 count of targets, T2 letter, T3 target floor position (x, z in world
// units), T4 count of objects of the target kind.
struct Answer {
  Task task = Task::T1;
  int count = 0;                   // T1, T4
  char letter = 0;                 // T2: one of C K R X Y
  glm::vec2 position{0.0f};        // T3: world (x, z)
  std::string target_kind;         // T3, T4: the kind shown in the "find this" panel
};

// Where the trial starts and how the camera may move.
struct CameraStart {
  enum class Mode { orbit, walk } mode = Mode::orbit;
  glm::vec3 target{0.0f};          // orbit: centre of the orbit
  float distance = 0.0f;           // orbit: fixed distance from the centre
  glm::vec3 position{0.0f};        // walk: eye position (eye height above the floor)
  float yaw = 0.0f;                // radians; 0 looks along -z
  float pitch = 0.0f;              // radians; walk mode keeps 0
  float fov_y = 0.785398f;         // radians
  float near_plane = 0.1f, far_plane = 1000.0f;
};

struct Scene {
  Kind kind = Kind::abstract;
  Task task = Task::T1;
  std::uint64_t seed = 0;
  std::vector<Mesh> meshes;
  std::vector<Object> objects;
  Answer answer;
  CameraStart camera;
  glm::vec3 bounds_min{0.0f}, bounds_max{0.0f};  // world-space box holding every object
  std::optional<FloorPlan> plan;   // WALKTHROUGH only
  std::string hash;                // SHA-256 of the canonical serialization (scene/hash.h)
};

}  // namespace dtlab::scene
