// OBJ + MTL writer; see obj.h. Normals are transformed by the inverse
// transpose of the object's transform and renormalized.
#include "study/scene/obj.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "study/scene/generate.h"

namespace dtlab::scene {
namespace {

using Rgb8 = std::tuple<int, int, int>;

int channel(float v) {
  const float c = v < 0.0f ? 0.0f : (v > 1.0f ? 1.0f : v);
  return static_cast<int>(c * 255.0f + 0.5f);
}

std::string material_name(const Rgb8& c) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "c%02x%02x%02x", std::get<0>(c), std::get<1>(c), std::get<2>(c));
  return buf;
}

Rgb8 rgb8(glm::vec3 c) { return {channel(c.x), channel(c.y), channel(c.z)}; }

}  // namespace

void write_obj(const Scene& scene, std::ostream& obj, std::ostream& mtl, std::string_view mtl_name) {
  char line[160];
  obj << "# dtlab scene " << kind_name(scene.kind) << " " << task_name(scene.task) << " seed " << scene.seed << "\n"
      << "# hash " << scene.hash << "\n"
      << "mtllib " << mtl_name << "\n";
  std::map<Rgb8, bool> materials;  // ordered: the MTL file lists them sorted
  std::size_t base = 1;            // OBJ indices are 1-based and global
  for (const Object& o : scene.objects) {
    const Mesh& mesh = scene.meshes.at(o.mesh);
    obj << "o " << o.kind << "_" << o.id << "\ng " << o.kind << "_" << o.id << "\n";
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(o.transform)));
    for (const Vertex& v : mesh.vertices) {
      const glm::vec3 p = glm::vec3(o.transform * glm::vec4(v.position, 1.0f));
      std::snprintf(line, sizeof line, "v %.5f %.5f %.5f\n", static_cast<double>(p.x), static_cast<double>(p.y),
                    static_cast<double>(p.z));
      obj << line;
    }
    for (const Vertex& v : mesh.vertices) {
      const glm::vec3 n = glm::normalize(normal_matrix * v.normal);
      std::snprintf(line, sizeof line, "vn %.5f %.5f %.5f\n", static_cast<double>(n.x), static_cast<double>(n.y),
                    static_cast<double>(n.z));
      obj << line;
    }
    // Faces grouped by material, in order of first appearance.
    std::vector<Rgb8> order;
    std::map<Rgb8, std::vector<std::size_t>> faces;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const Rgb8 c = rgb8(o.color * mesh.vertices[mesh.indices[t]].color);
      auto [it, inserted] = faces.try_emplace(c);
      if (inserted) order.push_back(c);
      it->second.push_back(t);
      materials[c] = true;
    }
    for (const Rgb8& c : order) {
      obj << "usemtl " << material_name(c) << "\n";
      for (std::size_t t : faces[c]) {
        const std::size_t a = base + mesh.indices[t], b = base + mesh.indices[t + 1], d = base + mesh.indices[t + 2];
        obj << "f " << a << "//" << a << " " << b << "//" << b << " " << d << "//" << d << "\n";
      }
    }
    base += mesh.vertices.size();
  }
  mtl << "# dtlab scene materials: one per colour (diffuse = the colour, a little ambient)\n";
  for (const auto& [c, used] : materials) {
    (void)used;
    const double r = std::get<0>(c) / 255.0, g = std::get<1>(c) / 255.0, b = std::get<2>(c) / 255.0;
    std::snprintf(line, sizeof line, "newmtl %s\nKa %.4f %.4f %.4f\nKd %.4f %.4f %.4f\nKs 0 0 0\nd 1\nillum 1\n\n",
                  material_name(c).c_str(), 0.2 * r, 0.2 * g, 0.2 * b, r, g, b);
    mtl << line;
  }
}

Status save_obj(const Scene& scene, const std::string& obj_path) {
  const std::filesystem::path path(obj_path);
  std::filesystem::path mtl_path = path;
  mtl_path.replace_extension(".mtl");
  if (mtl_path == path) return Error{obj_path, 0, 0, "", "the OBJ file must not end in .mtl"};
  std::ofstream obj(path, std::ios::binary), mtl(mtl_path, std::ios::binary);
  if (!obj) return Error{obj_path, 0, 0, "", std::string("cannot open for writing: ") + std::strerror(errno)};
  if (!mtl) return Error{mtl_path.string(), 0, 0, "", std::string("cannot open for writing: ") + std::strerror(errno)};
  write_obj(scene, obj, mtl, mtl_path.filename().string());
  obj.close();
  mtl.close();
  if (!obj) return Error{obj_path, 0, 0, "", "write failed (disk full?)"};
  if (!mtl) return Error{mtl_path.string(), 0, 0, "", "write failed (disk full?)"};
  return {};
}

}  // namespace dtlab::scene
