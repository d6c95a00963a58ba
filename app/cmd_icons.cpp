// `dtlab icons --out DIR [--size N] [--sheet FILE.png] [--json]`: renders the
// "find this" panel icon of every WALKTHROUGH object kind headless (OSMesa,
// standard method) as DIR/<kind>.png with a transparent background, and the
// contact sheet of all kinds with their names (default DIR/contact_sheet.png).
// --json prints {"icons": [{"kind", "family", "file", "coverage"}], "sheet"}.
// Exit 2 bad command line (size out of range), 3 no GL context, directory not
// creatable or PNG not written. Never writes outside DIR and the sheet path.
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <system_error>

#include "app/commands.h"
#include "app/platform/gl_context.h"
#include "study/icons/icons.h"

namespace dtlab::app {

namespace {

struct IconsOptions {
  std::string out, sheet;
  int size = 96;
  bool json = false;
};

void run(const IconsOptions& o) {
  namespace fs = std::filesystem;
  const fs::path dir(o.out);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    fail("icons", kExitFailure, o.out + ": cannot create the output directory (" +
                           (ec ? ec.message() : std::string("a file of that name exists")) + ")");
  const std::string sheet_path = o.sheet.empty() ? (dir / "contact_sheet.png").string() : o.sheet;

  auto ctx = platform::create_headless(16, 16);
  if (!ctx) fail("icons", kExitFailure, "no headless GL context: " + ctx.error().to_string());
  icons::IconOptions options;
  options.size = o.size;
  auto all = icons::render_all(options);
  if (!all) fail("icons", kExitFailure, all.error().to_string());

  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const icons::Icon& ic : all.value()) {
    const std::string file = (dir / (std::string(ic.model->kind) + ".png")).string();
    if (Status st = icons::save_png(ic.image, file); !st) fail("icons", kExitFailure, st.error().to_string());
    list.push_back({{"kind", ic.model->kind},
                    {"family", ic.model->family},
                    {"file", file},
                    {"coverage", icons::coverage(ic.image)}});
  }
  const render::Image sheet = icons::contact_sheet(all.value());
  if (Status st = icons::save_png(sheet, sheet_path); !st) fail("icons", kExitFailure, st.error().to_string());

  if (o.json) {
    const nlohmann::ordered_json j{{"icons", list}, {"sheet", sheet_path}};
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << "wrote " << list.size() << " icons (" << o.size << "x" << o.size << ") to " << o.out << "\n";
  for (const auto& e : list)
    std::cout << "  " << e["kind"].get<std::string>() << "  coverage " << e["coverage"].get<double>() << "\n";
  std::cout << "contact sheet " << sheet_path << " (" << sheet.width << "x" << sheet.height << ")\n";
}

}  // namespace

void add_icons_command(CLI::App& root) {
  auto* cmd = root.add_subcommand("icons", "Render the 'find this' icon of every WALKTHROUGH object kind and a contact sheet");
  auto o = std::make_shared<IconsOptions>();
  cmd->add_option("--out", o->out, "Directory for the icons, one <kind>.png each (created if missing)")->required();
  cmd->add_option("--size", o->size, "Icon side in pixels")->check(CLI::Range(icons::kMinSize, icons::kMaxSize));
  cmd->add_option("--sheet", o->sheet, "Contact sheet PNG (default: DIR/contact_sheet.png)");
  cmd->add_flag("--json", o->json,
                "Print {\"icons\": [{\"kind\", \"family\", \"file\", \"coverage\"}], \"sheet\"} as JSON");
  cmd->footer(
      "Each icon is the model alone at the origin, seen from a 3/4 view (front and +z side, from\n"
      "above) whose frustum is fitted to the mesh, drawn by the standard method with a headlight,\n"
      "4x4 supersampled; the background is transparent (alpha 0). coverage: the share of the icon\n"
      "the model covers (mean alpha). The sheet shows every kind by family with its name.\n"
      "Exit status: 0 ok, 2 bad command line (size outside 16..1024), 3 no GL context or a file\n"
      "or directory not written.");
  cmd->callback([o] { run(*o); });
}

}  // namespace dtlab::app
