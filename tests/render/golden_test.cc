// Golden-image tests (64×48 frames of both renderers, compared with a
// tolerance) and validity of the vector outputs: SVG parses (libxml2), PDF
// renders with pdftoppm, PostScript with Ghostscript.
//
// Regenerate the goldens with ASGARD_UPDATE_GOLDEN=1 and look at them.
#include <gtest/gtest.h>
#ifdef ASGARD_HAVE_LIBXML2
#include <libxml/parser.h>
#endif

#include <cstdlib>

#include "core/render/image.h"
#include "core/render/sampler.h"
#include "core/render/shaded.h"
#include "core/render/wire.h"
#include "tests/render/test_util.h"

namespace asgard::render {
namespace {

using testing::SimulateFile;

constexpr int kW = 64, kH = 48;

// Mean channel difference ≤ 2 (of 255) and at most 1.5 % of pixels off by
// more than 48: tolerant of rasteriser and antialiasing differences between
// Mesa and Cairo builds, not of a moved, recoloured or missing body.
void ExpectMatchesGolden(const Image& image, const std::string& name) {
  const std::string golden = testing::SourcePath("tests/render/golden/" + name + ".png");
  const std::string actual = std::string(ASGARD_BINARY_DIR) + "/" + name + ".actual.png";
  ASSERT_TRUE(WritePng(image, actual));
  if (std::getenv("ASGARD_UPDATE_GOLDEN")) {
    ASSERT_TRUE(WritePng(image, golden));
    GTEST_SKIP() << "golden written: " << golden;
  }
  std::string error;
  const auto expected = ReadPng(golden, &error);
  ASSERT_TRUE(expected) << error;
  const ImageDifference d = Compare(image, *expected);
  ASSERT_TRUE(d.same_size);
  EXPECT_LE(d.mean, 2.0) << name << ": compare " << actual << " with " << golden;
  EXPECT_LE(d.fraction_over, 0.015) << name << ": compare " << actual << " with " << golden;
}

struct Fixture {
  pipeline::Run run;
  std::unique_ptr<SceneSampler> sampler;
  FrameInput frame;

  Fixture(const std::string& scene, double t, std::optional<ViewState> view = std::nullopt)
      : run(SimulateFile(scene)) {
    if (!run.ok) return;
    sampler = std::make_unique<SceneSampler>(run.scene, *run.equations, *run.simulation);
    const ViewState v = view.value_or(*sampler->SceneView());
    frame.sampler = sampler.get();
    frame.t = t;
    frame.poses = sampler->Poses(t);
    frame.camera = MakeCamera(v, kW, kH);
    frame.view_radius = v.radius / v.scale;
  }
};

// The pendulum's ball is knocked far away, so the whole-animation framing is
// wide; the goldens look at the two rods.
ViewState PendulumCloseUp() {
  ViewState v;
  v.rotation = DefaultTilt();
  v.center = Eigen::Vector3d(-8, -6, 0);
  v.radius = 12;
  return v;
}

TEST(Golden, ShadedColours) {
  Fixture f("tests/render/scenes/colours.al", 0.5);
  ASSERT_TRUE(f.run.ok);
  ShadedRenderer r(kW, kH);
  ASSERT_TRUE(r.ok()) << r.error();
  ExpectMatchesGolden(r.Render(*f.sampler, f.frame.poses, f.frame.camera, f.sampler->SceneLights()),
                      "shaded_colours");
}

TEST(Golden, ShadedPendulum) {
  Fixture f("samples/pendulum.al", 1.0, PendulumCloseUp());
  ASSERT_TRUE(f.run.ok);
  ShadedStyle style;
  style.supersample = 4;
  ShadedRenderer r(kW, kH, style);
  ASSERT_TRUE(r.ok()) << r.error();
  ExpectMatchesGolden(r.Render(*f.sampler, f.frame.poses, f.frame.camera, {}), "shaded_pendulum");
}

TEST(Golden, WireColoursWithOverlays) {
  Fixture f("tests/render/scenes/colours.al", 0.5);
  ASSERT_TRUE(f.run.ok);
  Overlays o;
  o.handles = o.paths = true;
  const auto paths = f.sampler->Paths(f.sampler->FrameTimes());
  f.frame.paths = &paths;
  ExpectMatchesGolden(RenderWire(f.frame, o), "wire_colours");
}

TEST(Golden, WirePendulumWithForces) {
  Fixture f("samples/pendulum.al", 1.0, PendulumCloseUp());
  ASSERT_TRUE(f.run.ok);
  Overlays o;
  o.forces = o.links = true;
  ExpectMatchesGolden(RenderWire(f.frame, o), "wire_pendulum");
}

class VectorOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    fixture_ = std::make_unique<Fixture>("samples/pendulum.al", 1.0, PendulumCloseUp());
    ASSERT_TRUE(fixture_->run.ok);
    // A directory per test: ctest runs tests in parallel processes.
    dir_ = testing::ScratchDir(std::string("vector-") +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  bool Write(const std::string& path, VectorDocument::Format format, int pages) {
    VectorDocument doc(path, format, 320, 240);
    if (!doc.ok()) return false;
    FrameInput f = fixture_->frame;
    f.camera = MakeCamera(PendulumCloseUp(), 320, 240);
    Overlays o;
    o.handles = o.forces = true;
    for (int k = 0; k < pages; ++k) {
      f.t = 0.5 * k;
      f.poses = fixture_->sampler->Poses(f.t);
      doc.AddPage(f, o);
    }
    return doc.Finish();
  }
  std::unique_ptr<Fixture> fixture_;
  std::string dir_;
};

TEST_F(VectorOutput, SvgParses) {
  const std::string path = dir_ + "/p.svg";
  ASSERT_TRUE(Write(path, VectorDocument::Format::kSvg, 1));
  EXPECT_NE(testing::ReadText(path).find("<path"), std::string::npos);
#ifdef ASGARD_HAVE_LIBXML2
  xmlDocPtr doc = xmlReadFile(path.c_str(), nullptr, XML_PARSE_NONET);
  ASSERT_NE(doc, nullptr);
  const xmlNode* root = xmlDocGetRootElement(doc);
  ASSERT_NE(root, nullptr);
  EXPECT_STREQ(reinterpret_cast<const char*>(root->name), "svg");
  xmlFreeDoc(doc);
#else
  GTEST_SKIP() << "libxml2 (libxml2-dev) is not installed; the SVG was not parsed";
#endif
}

TEST_F(VectorOutput, PdfRendersWithPdftoppm) {
  if (!testing::HaveProgram("pdftoppm"))
    GTEST_SKIP() << "pdftoppm (poppler-utils) is not installed";
  const std::string path = dir_ + "/p.pdf";
  ASSERT_TRUE(Write(path, VectorDocument::Format::kPdf, 3));
  ASSERT_EQ(testing::Run("pdftoppm -png -r 36 -f 3 -l 3 '" + path + "' '" + dir_ + "/page'"), 0);
  const auto page = ReadPng(dir_ + "/page-3.png");
  ASSERT_TRUE(page) << "pdftoppm wrote no third page";
  int ink = 0;
  for (size_t i = 0; i < page->rgb.size(); i += 3) ink += page->rgb[i] < 128;
  EXPECT_GT(ink, 20);
}

TEST_F(VectorOutput, PostScriptRendersWithGhostscript) {
  if (!testing::HaveProgram("gs")) GTEST_SKIP() << "Ghostscript (gs) is not installed";
  const std::string path = dir_ + "/p.ps";
  ASSERT_TRUE(Write(path, VectorDocument::Format::kPs, 2));
  EXPECT_EQ(testing::ReadText(path).substr(0, 4), "%!PS");
  EXPECT_EQ(testing::Run("gs -q -dSAFER -dNOPAUSE -dBATCH -sDEVICE=nullpage '" + path + "' > '" +
                         dir_ + "/gs.log' 2>&1"),
            0)
      << testing::ReadText(dir_ + "/gs.log");
}

}  // namespace
}  // namespace asgard::render
