// The dochost command line: exit codes, conversions between flavours, the
// PDF of the memo rasterised with pdftoppm (text and a non-empty animation
// frame), recompute with a refreshed poster, restart leaving the document
// alone, and a crashed slave in a page.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/render/image.h"
#include "formats/document/file.h"
#include "tests/document/exec.h"

namespace {

namespace fs = std::filesystem;
const std::string kDochost = std::string(ASGARD_BINARY_DIR) + "/host-shim/dochost";
const std::string kSamples = std::string(ASGARD_SOURCE_DIR) + "/samples/";

fs::path Scratch(const std::string& name) {
  const fs::path dir = fs::path(ASGARD_BINARY_DIR) / "tests/document/scratch_cli" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

using asgard::testing::Exec;
using Result = asgard::testing::Result;

std::string Read(const fs::path& p) {
  std::string s;
  asgard::document::ReadFile(p.string(), s, nullptr);
  return s;
}

TEST(Dochost, ExitCodesFollowTheAsgardConventions) {
  EXPECT_EQ(Exec(kDochost + " --help").status, 0);
  EXPECT_EQ(Exec(kDochost + " convert --help").status, 0);
  EXPECT_EQ(Exec(kDochost).status, 2);
  EXPECT_EQ(Exec(kDochost + " convert " + kSamples + "memo.ens").status, 2);
  EXPECT_EQ(Exec(kDochost + " convert " + kSamples + "memo.ens -o x.doc").status, 2);
  EXPECT_EQ(Exec(kDochost + " verb " + kSamples + "memo.ens frob").status, 2);
  const Result missing = Exec(kDochost + " convert /nonexistent.ens -o /tmp/x.pdf");
  EXPECT_EQ(missing.status, 1);
  EXPECT_NE(missing.out.find("cannot read '/nonexistent.ens'"), std::string::npos);
  const fs::path dir = Scratch("bad");
  asgard::document::WriteFileAtomic((dir / "bad.ens").string(), "DOCUMENT X\n<X>\n{x</X>", nullptr);
  const Result bad = Exec(kDochost + " convert " + (dir / "bad.ens").string() + " -o " +
                          (dir / "out.pdf").string());
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.out.find("bad.ens:3:1: error: unterminated text"), std::string::npos) << bad.out;
  EXPECT_FALSE(fs::exists(dir / "out.pdf"));
}

TEST(Dochost, ConvertsBetweenFlavoursByteExactly) {
  const fs::path dir = Scratch("flavours");
  for (const char* name : {"memo", "two-animations"}) {
    const std::string in = kSamples + name + ".ens";
    const std::string xml = (dir / (std::string(name) + ".xml")).string();
    const std::string back = (dir / (std::string(name) + ".ens")).string();
    ASSERT_EQ(Exec(kDochost + " convert " + in + " -o " + xml + " --quiet").status, 0);
    ASSERT_EQ(Exec(kDochost + " convert " + xml + " -o " + back + " --quiet").status, 0);
    EXPECT_EQ(Read(back), Read(in));
  }
}

// Mean and spread of the darkness in a box of an image (pixels).
struct Ink {
  int dark = 0, total = 0, distinct = 0;
};
Ink Measure(const asgard::render::Image& img, int x0, int y0, int x1, int y1) {
  Ink ink;
  std::vector<bool> seen(4096, false);
  for (int y = std::max(0, y0); y < std::min(img.height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width, x1); ++x) {
      const uint8_t* p = img.Pixel(x, y);
      ++ink.total;
      if (p[0] + p[1] + p[2] < 3 * 128) ++ink.dark;
      const int key = (p[0] >> 4) << 8 | (p[1] >> 4) << 4 | (p[2] >> 4);
      if (!seen[key]) seen[key] = true, ++ink.distinct;
    }
  return ink;
}

TEST(Dochost, TheMemoPdfShowsItsTextAndANonEmptyAnimationFrame) {
  const fs::path dir = Scratch("pdf");
  const std::string pdf = (dir / "memo.pdf").string(), layout = (dir / "layout.json").string();
  const Result r = Exec(kDochost + " convert " + kSamples + "memo.ens -o " + pdf +
                        " --time 1.5 --layout " + layout);
  ASSERT_EQ(r.status, 0) << r.out;
  const Result text = Exec("pdftotext " + pdf + " -");
  ASSERT_EQ(text.status, 0) << text.out;
  for (const char* words : {"Whom it may concern", "Wayne", "Asgard within Ensemble",
                            "Thanks to Vance for putting this example together"})
    EXPECT_NE(text.out.find(words), std::string::npos) << words << "\n" << text.out;
  ASSERT_EQ(Exec("pdftoppm -r 72 -png -singlefile " + pdf + " " + (dir / "page").string()).status,
            0);
  auto img = asgard::render::ReadPng((dir / "page.png").string());
  ASSERT_TRUE(img);
  const auto json = nlohmann::json::parse(Read(layout));
  const auto& items = json["pages"][0];
  ASSERT_EQ(items.size(), 5u);
  // The text blocks have ink.
  for (const auto& b : items) {
    const int x = b["x"].get<double>(), y = b["y"].get<double>();
    const int w = b["w"].get<double>(), h = b["h"].get<double>();
    const Ink ink = Measure(*img, x + 2, y + 2, x + w - 2, y + h - 2);
    if (b["kind"] == "embedded") {
      EXPECT_GT(ink.distinct, 20) << "shaded spheres, not a flat box";
      EXPECT_GT(ink.total - ink.dark, ink.total / 2) << "mostly background";
    } else {
      EXPECT_GT(ink.dark, 20) << b.dump();
    }
  }
}

TEST(Dochost, RecomputeRefreshesThePosterAndAKilledSlaveStillGivesAPage) {
  const fs::path dir = Scratch("recompute");
  const std::string doc = (dir / "memo.ens").string();
  fs::copy_file(kSamples + "memo.ens", doc);
  const Result r = Exec(kDochost + " verb " + doc + " recompute --time 1");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::string with = Read(dir / "memo.ens");
  EXPECT_NE(with.find("</ASGARD>\n<POSTER>\n{"), std::string::npos);
  // The slave cannot start: the page shows the stored poster and the reason.
  const Result p = Exec(kDochost + " convert " + doc + " -o " + (dir / "p.png").string() +
                        " --core /nonexistent/asgard-core --dpi 72");
  EXPECT_EQ(p.status, 3) << "written, with the poster for the animation: " << p.out;
  EXPECT_NE(p.out.find("cannot start '/nonexistent/asgard-core'"), std::string::npos) << p.out;
  auto img = asgard::render::ReadPng((dir / "p.png").string());
  ASSERT_TRUE(img);
  EXPECT_GT(Measure(*img, 120, 120, 475, 355).distinct, 20) << "the poster is drawn";
  EXPECT_EQ(Read(dir / "memo.ens"), with) << "the document is untouched";
}

TEST(Dochost, RestartOnlyRestartsTheSlaveAndLeavesTheDocumentAlone) {
  const fs::path dir = Scratch("restart");
  const std::string doc = (dir / "memo.ens").string();
  fs::copy_file(kSamples + "memo.ens", doc);
  const std::string before = Read(doc);
  const auto written = fs::last_write_time(doc);
  const Result r = Exec(kDochost + " verb " + doc + " restart");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("animation 1: restarted: 2 bodies"), std::string::npos) << r.out;
  EXPECT_EQ(Read(doc), before) << "restart must not rewrite the document";
  EXPECT_EQ(fs::last_write_time(doc), written);
  // With -o the result goes to OUT, and IN is still untouched.
  const Result o = Exec(kDochost + " verb " + doc + " restart -o " + (dir / "out.ens").string());
  ASSERT_EQ(o.status, 0) << o.out;
  EXPECT_TRUE(fs::exists(dir / "out.ens"));
  EXPECT_EQ(Read(doc), before);
}

TEST(Dochost, HostVerbsRunHeadless) {
  const fs::path dir = Scratch("verbs");
  const std::string memo = kSamples + "memo.ens";
  Result r = Exec(kDochost + " verb " + memo + " play --to 0.1 -o " + (dir / "f.png").string());
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("played 4 frames"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "f_0003.png"));
  r = Exec(kDochost + " verb " + memo + " handles on -o " + (dir / "h.png").string());
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("handles shown"), std::string::npos);
  r = Exec(kDochost + " verb " + memo + " seek 2.5");
  EXPECT_NE(r.out.find("at t = 2.5 s"), std::string::npos) << r.out;
  r = Exec(kDochost + " verb " + memo + " viewer -o " + (dir / "v.html").string());
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(Read(dir / "v.html").find("shape_set ss1 -desc {-sub"), std::string::npos);
  r = Exec(kDochost + " verb " + memo + " status");
  EXPECT_NE(r.out.find("animation 1 <ASGARD>: 2 bodies, t = 0 .. 3 s"), std::string::npos) << r.out;
  EXPECT_EQ(Exec(kDochost + " verb " + memo + " seek 1 --animation 2").status, 1);
}

}  // namespace
