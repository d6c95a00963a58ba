// OBJ + MTL export read back by a small independent reader: every object is
// an `o`, every face index is in range and 1-based, every material used is
// defined in the MTL, and vertex and face counts match the scene.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "study/scene/generate.h"
#include "study/scene/obj.h"
#include "tests/scene/mesh_checks.h"

namespace dtlab::scene {
namespace {

struct ObjFile {
  std::size_t v = 0, vn = 0, f = 0, objects = 0;
  std::string mtllib;
  std::set<std::string> used;
  std::vector<glm::vec3> positions;
  std::string error;  // first problem found, empty if none
};

ObjFile read_obj(const std::string& text) {
  ObjFile o;
  std::istringstream in(text);
  std::string line;
  int lineno = 0;
  std::vector<std::array<long, 6>> faces;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    auto fail = [&](const std::string& what) {
      if (o.error.empty()) o.error = "line " + std::to_string(lineno) + ": " + what + ": " + line;
    };
    if (tag == "v" || tag == "vn") {
      glm::vec3 p;
      if (!(ls >> p.x >> p.y >> p.z)) fail("expected 3 numbers");
      if (tag == "v") ++o.v, o.positions.push_back(p);
      else {
        ++o.vn;
        if (std::abs(glm::length(p) - 1.0f) > 1e-3f) fail("normal not unit");
      }
    } else if (tag == "f") {
      std::array<long, 6> idx{};
      for (int k = 0; k < 3; ++k) {
        std::string vert;
        ls >> vert;
        const auto slash = vert.find("//");
        if (slash == std::string::npos) {
          fail("expected v//vn");
          break;
        }
        idx[2 * k] = std::stol(vert.substr(0, slash));
        idx[2 * k + 1] = std::stol(vert.substr(slash + 2));
      }
      std::string extra;
      if (ls >> extra) fail("more than 3 vertices");
      faces.push_back(idx);
      ++o.f;
    } else if (tag == "o") {
      ++o.objects;
    } else if (tag == "usemtl") {
      std::string m;
      ls >> m;
      o.used.insert(m);
    } else if (tag == "mtllib") {
      ls >> o.mtllib;
    } else if (tag != "g") {
      fail("unknown statement");
    }
  }
  for (const auto& f : faces)
    for (int k = 0; k < 6; ++k) {
      const long n = static_cast<long>(k % 2 == 0 ? o.v : o.vn);
      if (f[static_cast<std::size_t>(k)] < 1 || f[static_cast<std::size_t>(k)] > n) o.error = "face index out of range";
    }
  return o;
}

std::set<std::string> read_mtl(const std::string& text) {
  std::set<std::string> names;
  std::istringstream in(text);
  std::string tag, name;
  while (in >> tag)
    if (tag == "newmtl" && in >> name) names.insert(name);
  return names;
}

struct SceneCase {
  Kind kind;
  Task task;
};
void PrintTo(const SceneCase& c, std::ostream* os) {  // readable ctest names
  *os << kind_name(c.kind) << ' ' << task_name(c.task);
}

class ObjExport : public ::testing::TestWithParam<SceneCase> {};

TEST_P(ObjExport, ReadsBackAsValidObj) {
  const auto [kind, task] = GetParam();
  const auto s = generate(kind, task, 77);
  ASSERT_TRUE(s.ok());
  std::ostringstream obj, mtl;
  write_obj(*s, obj, mtl, "scene.mtl");
  const ObjFile f = read_obj(obj.str());
  EXPECT_EQ(f.error, "");
  EXPECT_EQ(f.mtllib, "scene.mtl");
  EXPECT_EQ(f.objects, s->objects.size());
  std::size_t vertices = 0;
  for (const Object& o : s->objects) vertices += s->meshes[o.mesh].vertices.size();
  EXPECT_EQ(f.v, vertices);
  EXPECT_EQ(f.vn, vertices);
  EXPECT_EQ(f.f, testing::scene_triangles(*s));
  const auto defined = read_mtl(mtl.str());
  EXPECT_FALSE(f.used.empty());
  for (const auto& m : f.used) EXPECT_TRUE(defined.count(m)) << "material " << m << " used but not defined";
  // Positions are world space: the first object's first vertex, transformed.
  const Object& first = s->objects.front();
  const glm::vec3 expect = testing::world(first, s->meshes[first.mesh].vertices.front());
  EXPECT_NEAR(glm::length(f.positions.front() - expect), 0.0f, 1e-3f);
  if (kind == Kind::abstract) {
    EXPECT_TRUE(f.used.count("cff0000")) << "targets are pure red";
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, ObjExport,
                         ::testing::Values(SceneCase{Kind::abstract, Task::T1}, SceneCase{Kind::abstract, Task::T2},
                                           SceneCase{Kind::walkthrough, Task::T3},
                                           SceneCase{Kind::walkthrough, Task::T4}),
                         [](const auto& info) {
                           return std::string(kind_name(info.param.kind)) + std::string(task_name(info.param.task));
                         });

TEST(ObjExport, SavesBothFilesAndReportsUnwritablePaths) {
  const auto dir = std::filesystem::temp_directory_path() / ("dtlab_obj_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto s = generate(Kind::abstract, Task::T1, 5);
  ASSERT_TRUE(s.ok());
  ASSERT_TRUE(save_obj(*s, (dir / "a.obj").string()).ok());
  EXPECT_GT(std::filesystem::file_size(dir / "a.obj"), 100000u);
  std::ifstream obj(dir / "a.obj");
  std::stringstream text;
  text << obj.rdbuf();
  EXPECT_EQ(read_obj(text.str()).mtllib, "a.mtl");
  EXPECT_TRUE(std::filesystem::exists(dir / "a.mtl"));
  const Status bad = save_obj(*s, (dir / "missing" / "b.obj").string());
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().file.find("missing"), std::string::npos);
  EXPECT_FALSE(save_obj(*s, (dir / "c.mtl").string()).ok()) << "an OBJ named .mtl would overwrite its own materials";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace dtlab::scene
