// path_svg (path.h): hand-written SVG of a few primitives (the format is
// plain text; no library is needed to emit it), every number printed with
// fixed precision so the output is stable.
#include "study/replay/path.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dtlab::replay {

namespace {

const char* kColours[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

}  // namespace

double walked_distance(const std::vector<store::CameraPose>& poses) {
  double d = 0;
  for (std::size_t i = 1; i < poses.size(); ++i) d += std::hypot(poses[i].x - poses[i - 1].x, poses[i].z - poses[i - 1].z);
  return d;
}

PathPanel path_panel(const scene::FloorPlan& plan, glm::vec3 start, const std::vector<WalkedPath>& paths, int side,
                     const std::string& title) {
  const double margin = 24, legend = 22.0 * static_cast<double>(paths.size()) + (title.empty() ? 0 : 26);
  const double cells = std::max(plan.width, plan.height);
  const double cell = (side - 2 * margin) / std::max(1.0, cells);
  const double top = margin + legend;
  auto X = [&](double world_x) { return num(margin + world_x / plan.cell_size * cell); };
  auto Y = [&](double world_z) { return num(top + world_z / plan.cell_size * cell); };
  auto cx = [&](double c) { return num(margin + c * cell); };
  auto cy = [&](double c) { return num(top + c * cell); };
  const bool key = side >= 480;  // the marker key fits beside the label; narrower panels leave it to the title
  PathPanel panel;
  panel.width = side;
  panel.height = top + plan.height * cell + margin;
  std::string& s = panel.markup;
  double ly = margin * 0.6;
  if (!title.empty()) {
    s += "<text x=\"" + num(margin) + "\" y=\"" + num(ly + 12) + "\" font-size=\"16\">" + escape(title) + "</text>\n";
    ly += 26;
  }
  s += "<rect x=\"" + cx(0) + "\" y=\"" + cy(0) + "\" width=\"" + num(plan.width * cell) + "\" height=\"" +
       num(plan.height * cell) + "\" fill=\"#faf8f0\" stroke=\"#3c3c46\" stroke-width=\"3\"/>\n";
  auto room = [&](int x, int y) { return plan.room[static_cast<std::size_t>(y * plan.width + x)]; };
  auto door = [&](int x0, int y0, int x1, int y1) {
    return std::any_of(plan.doors.begin(), plan.doors.end(), [&](const scene::FloorPlan::Door& d) {
      return (d.x0 == x0 && d.y0 == y0 && d.x1 == x1 && d.y1 == y1) || (d.x0 == x1 && d.y0 == y1 && d.x1 == x0 && d.y1 == y0);
    });
  };
  auto wall = [&](double x0, double y0, double x1, double y1) {
    s += "<line x1=\"" + cx(x0) + "\" y1=\"" + cy(y0) + "\" x2=\"" + cx(x1) + "\" y2=\"" + cy(y1) +
         "\" stroke=\"#3c3c46\" stroke-width=\"2\"/>\n";
  };
  for (int y = 0; y < plan.height; ++y)
    for (int x = 0; x < plan.width; ++x) {
      if (x + 1 < plan.width && room(x, y) != room(x + 1, y)) {
        if (door(x, y, x + 1, y)) {
          wall(x + 1, y, x + 1, y + 0.3);
          wall(x + 1, y + 0.7, x + 1, y + 1);
        } else {
          wall(x + 1, y, x + 1, y + 1);
        }
      }
      if (y + 1 < plan.height && room(x, y) != room(x, y + 1)) {
        if (door(x, y, x, y + 1)) {
          wall(x, y + 1, x + 0.3, y + 1);
          wall(x + 0.7, y + 1, x + 1, y + 1);
        } else {
          wall(x, y + 1, x + 1, y + 1);
        }
      }
    }
  s += "<circle cx=\"" + X(start.x) + "\" cy=\"" + Y(start.z) + "\" r=\"" + num(cell * 0.3) +
       "\" fill=\"#2856dc\"/><text x=\"" + num(margin + start.x / plan.cell_size * cell + cell * 0.4) + "\" y=\"" +
       Y(start.z) + "\" fill=\"#2856dc\">start</text>\n";
  for (std::size_t i = 0; i < paths.size(); ++i) {
    const WalkedPath& p = paths[i];
    const std::string colour = kColours[i % std::size(kColours)];
    if (!p.poses.empty()) {
      s += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"2\" stroke-linejoin=\"round\" points=\"";
      for (const auto& pose : p.poses) s += X(pose.x) + "," + Y(pose.z) + " ";
      s += "\"/>\n";
    }
    if (p.target)
      s += "<circle cx=\"" + X(p.target->x) + "\" cy=\"" + Y(p.target->y) + "\" r=\"" + num(cell * 0.28) +
           "\" fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"3\"/>\n";
    if (p.answer) {
      const double r = cell * 0.25;
      const double ax = margin + p.answer->x / plan.cell_size * cell, ay = top + p.answer->y / plan.cell_size * cell;
      s += "<path d=\"M" + num(ax - r) + "," + num(ay - r) + " L" + num(ax + r) + "," + num(ay + r) + " M" + num(ax - r) +
           "," + num(ay + r) + " L" + num(ax + r) + "," + num(ay - r) + "\" stroke=\"" + colour +
           "\" stroke-width=\"3\"/>\n";
    }
    s += "<text x=\"" + num(margin) + "\" y=\"" + num(ly + 14) + "\" fill=\"" + colour + "\">" + escape(p.label) +
         ": walked " + num(walked_distance(p.poses)) + " units" +
         (key ? std::string(p.target ? ", o target" : "") + (p.answer ? ", x answer" : "") : "") + "</text>\n";
    ly += 22;
  }
  return panel;
}

std::string path_svg(const scene::FloorPlan& plan, glm::vec3 start, const std::vector<WalkedPath>& paths, int side,
                     const std::string& title) {
  return panels_svg({path_panel(plan, start, paths, side, title)}, 1, "");
}

std::string panels_svg(const std::vector<PathPanel>& panels, int columns, const std::string& title) {
  const double gap = 8, head = title.empty() ? 0 : 34;
  columns = std::max(1, columns);
  std::vector<double> row_height;  // each row as tall as its tallest panel
  double width = 0;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const std::size_t row = i / static_cast<std::size_t>(columns);
    if (row == row_height.size()) row_height.push_back(0);
    row_height[row] = std::max(row_height[row], panels[i].height);
    width = std::max(width, static_cast<double>(i % static_cast<std::size_t>(columns) + 1) * (panels[i].width + gap) - gap);
  }
  double height = head;
  for (double h : row_height) height += h + gap;
  std::string s = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(std::max(width, 1.0)) + "\" height=\"" +
                  num(std::max(height - (row_height.empty() ? 0 : gap), 1.0)) +
                  "\" font-family=\"sans-serif\" font-size=\"14\">\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!title.empty()) s += "<text x=\"12\" y=\"24\" font-size=\"18\">" + escape(title) + "</text>\n";
  double y = head, x = 0;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const std::size_t col = i % static_cast<std::size_t>(columns);
    if (col == 0 && i > 0) y += row_height[i / static_cast<std::size_t>(columns) - 1] + gap;
    x = col == 0 ? 0 : x + panels[i - 1].width + gap;
    const bool moved = x != 0 || y != 0;
    if (moved) s += "<g transform=\"translate(" + num(x) + "," + num(y) + ")\">\n";
    s += panels[i].markup;
    if (moved) s += "</g>\n";
  }
  s += "</svg>\n";
  return s;
}

WalkedPath walked_path(const scene::Scene& scene, const std::optional<store::Answer>& answer,
                       std::vector<store::CameraPose> poses, std::string label) {
  WalkedPath path;
  path.label = std::move(label);
  path.poses = std::move(poses);
  if (scene.task == scene::Task::T3) path.target = scene.answer.position;
  if (answer)
    if (const auto* p = std::get_if<store::Position>(&*answer)) path.answer = glm::vec2(p->x, p->z);
  return path;
}

}  // namespace dtlab::replay
