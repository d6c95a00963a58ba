// `dtlab icons`: the JSON contract, the PNG files it writes (read back with
// stb_image: size, transparent corners), and the exit codes for a bad size (2)
// and an output directory or sheet path that cannot be written (3).
#include <gtest/gtest.h>
#include <stb_image.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "study/scene/models.h"

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status;
  std::string out;  // stdout and stderr together
};

Outcome dtlab(const std::string& args, bool with_stderr = true) {
  const std::string cmd = std::string(DTLAB_BINARY) + " " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (pipe && std::fgets(buf, sizeof buf, pipe)) out += buf;
  const int rc = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, out};
}

struct TempDir {
  fs::path path = fs::temp_directory_path() / ("dtlab_icons_cli_" + std::to_string(::getpid()));
  TempDir() { fs::create_directories(path); }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

struct Png {
  int w = 0, h = 0;
  std::vector<unsigned char> rgba;
};
Png load(const std::string& path) {
  Png p;
  int n = 0;
  unsigned char* data = stbi_load(path.c_str(), &p.w, &p.h, &n, 4);
  if (data) {
    p.rgba.assign(data, data + static_cast<std::size_t>(p.w) * p.h * 4);
    stbi_image_free(data);
  }
  return p;
}

TEST(IconsCommand, WritesEveryKindAndTheSheetAndReportsThemAsJson) {
  TempDir tmp;
  const fs::path dir = tmp.path / "icons";
  const fs::path sheet = tmp.path / "sheet.png";
  const Outcome r = dtlab("icons --out " + dir.string() + " --size 48 --sheet " + sheet.string() + " --json", false);
  ASSERT_EQ(r.status, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("icons") && j.contains("sheet"));
  EXPECT_EQ(j["sheet"], sheet.string());
  const auto catalogue = dtlab::scene::model_catalogue();
  ASSERT_EQ(j["icons"].size(), catalogue.size());
  for (std::size_t i = 0; i < catalogue.size(); ++i) {
    const auto& e = j["icons"][i];
    for (const char* key : {"kind", "family", "file", "coverage"}) ASSERT_TRUE(e.contains(key)) << key;
    EXPECT_EQ(e["kind"], std::string(catalogue[i].kind));
    EXPECT_EQ(e["family"], std::string(catalogue[i].family));
    EXPECT_EQ(e["file"], (dir / (std::string(catalogue[i].kind) + ".png")).string());
    const double cov = e["coverage"].get<double>();
    EXPECT_GT(cov, 0.05);
    EXPECT_LT(cov, 0.9);
    const Png png = load(e["file"].get<std::string>());
    ASSERT_EQ(png.w, 48) << e["file"];
    ASSERT_EQ(png.h, 48);
    EXPECT_EQ(png.rgba[3], 0) << "transparent background kept in the PNG";
    long alpha = 0;
    for (std::size_t p = 3; p < png.rgba.size(); p += 4) alpha += png.rgba[p];
    EXPECT_NEAR(static_cast<double>(alpha) / (255.0 * 48 * 48), cov, 1e-9) << "coverage is the file's mean alpha";
  }
  const Png s = load(sheet.string());
  EXPECT_GT(s.w, 6 * 48);
  EXPECT_GT(s.h, 3 * 48);
}

TEST(IconsCommand, TextOutputAndDefaultSheetPath) {
  TempDir tmp;
  const Outcome r = dtlab("icons --out " + (tmp.path / "i").string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("wrote 14 icons (96x96)"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(tmp.path / "i" / "contact_sheet.png"));
  EXPECT_TRUE(fs::exists(tmp.path / "i" / "directors_chair.png"));
}

TEST(IconsCommand, BadSizeIsAUsageError) {
  TempDir tmp;
  for (const char* size : {"8", "0", "2000", "abc"}) {
    const Outcome r = dtlab("icons --out " + (tmp.path / "x").string() + " --size " + size);
    EXPECT_EQ(r.status, 2) << size << ": " << r.out;
    EXPECT_NE(r.out.find("--size"), std::string::npos) << r.out;
  }
  EXPECT_FALSE(fs::exists(tmp.path / "x")) << "nothing written on a usage error";
  EXPECT_EQ(dtlab("icons --size 48").status, 2) << "--out is required";
}

TEST(IconsCommand, UnwritableDirectoryOrSheetIsAnEnvironmentFailure) {
  TempDir tmp;
  std::ofstream(tmp.path / "file") << "x";
  const Outcome under_file = dtlab("icons --out " + (tmp.path / "file" / "icons").string());
  EXPECT_EQ(under_file.status, 3) << under_file.out;
  EXPECT_NE(under_file.out.find("cannot create the output directory"), std::string::npos) << under_file.out;
  const Outcome is_file = dtlab("icons --out " + (tmp.path / "file").string());
  EXPECT_EQ(is_file.status, 3) << is_file.out;
  const Outcome sheet = dtlab("icons --out " + (tmp.path / "ok").string() + " --size 16 --sheet " +
                              (tmp.path / "missing" / "sheet.png").string());
  EXPECT_EQ(sheet.status, 3) << sheet.out;
  EXPECT_NE(sheet.out.find("sheet.png"), std::string::npos) << sheet.out;
}

TEST(IconsCommand, HelpNamesTheOptions) {
  const Outcome r = dtlab("icons --help");
  EXPECT_EQ(r.status, 0);
  for (const char* s : {"--out", "--size", "--sheet", "--json", "Exit status"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s;
}

}  // namespace
