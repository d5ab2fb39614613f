// Export tests: frame names, Rayshade and POV-Ray files (POV-Ray renders
// them), glTF binary structure, movies checked with ffprobe, and the
// `asgard render` / `asgard export` command line.
#include "formats/export/export.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "core/render/image.h"
#include "tests/render/test_util.h"

namespace asgard::formats {
namespace {

using nlohmann::json;
namespace t = render::testing;

const std::string kAsgard = std::string(ASGARD_BINARY_DIR) + "/core/app/asgard";

struct Still {
  pipeline::Run run;
  std::unique_ptr<render::SceneSampler> sampler;
  StillScene scene;

  Still(const std::string& file, double time, int w = 64, int h = 48) : run(t::SimulateFile(file)) {
    if (!run.ok) return;
    sampler = std::make_unique<render::SceneSampler>(run.scene, *run.equations, *run.simulation);
    scene.sampler = sampler.get();
    scene.t = time;
    scene.camera = render::MakeCamera(*sampler->SceneView(), w, h);
    scene.lights = sampler->SceneLights();
  }
};

size_t Count(const std::string& text, const std::string& word) {
  size_t n = 0;
  for (size_t p = text.find(word); p != std::string::npos; p = text.find(word, p + 1)) ++n;
  return n;
}

TEST(FramePath, PatternsAndNumbering) {
  EXPECT_EQ(FramePath("out/f%04d.png", 7, 100), "out/f0007.png");
  EXPECT_EQ(FramePath("f%d.ppm", 12, 100), "f12.ppm");
  EXPECT_EQ(FramePath("out/frame.png", 3, 151), "out/frame_0003.png");
  EXPECT_EQ(FramePath("a.b/frame", 3, 20000), "a.b/frame_00003");
}

TEST(Rayshade, DescribesEveryPiece) {
  Still s("tests/render/scenes/colours.al", 0.5);
  ASSERT_TRUE(s.run.ok);
  const std::string path = t::ScratchDir("rayshade") + "/c.ray";
  std::string error;
  ASSERT_TRUE(WriteRayshade(path, s.scene, &error)) << error;
  const std::string text = t::ReadText(path);
  for (const char* key : {"\nscreen 64 48\n", "\neyep ", "\nlookp ", "\nup ", "\nfov ",
                          "point -6 8 10", " directional "})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  size_t spheres = 0, polys = 0;
  for (const auto& b : s.sampler->bodies())
    for (const auto& p : b.pieces) p.is_sphere ? ++spheres : polys += p.hull.faces.size();
  EXPECT_EQ(Count(text, "\nsphere "), spheres);
  EXPECT_EQ(Count(text, "\npoly "), polys);
}

TEST(PovRay, SceneRendersWithPovray) {
  Still s("tests/render/scenes/colours.al", 0.5);
  ASSERT_TRUE(s.run.ok);
  const std::string dir = t::ScratchDir("povray");
  std::string error;
  ASSERT_TRUE(WritePovray(dir + "/c.pov", s.scene, &error)) << error;
  const std::string text = t::ReadText(dir + "/c.pov");
  EXPECT_EQ(Count(text, "\nsphere {"), 3u);  // the ball and the two dumbbell ends
  EXPECT_EQ(Count(text, "\nmesh {"), 3u);    // red cube, dumbbell bar, grey cube
  if (!t::HaveProgram("povray"))
    GTEST_SKIP() << "povray is not installed; the file was not rendered";
  ASSERT_EQ(
      t::Run("cd '" + dir + "' && povray +Ic.pov +Oc.png +W64 +H48 -D -GA +FN > pov.log 2>&1"), 0)
      << t::ReadText(dir + "/pov.log");
  const auto img = render::ReadPng(dir + "/c.png", &error);
  ASSERT_TRUE(img) << error;
  EXPECT_EQ(img->width, 64);
  // The red cube is left of centre, the blue ball in the middle (as in the
  // shaded frame): look for a strongly red and a strongly blue pixel.
  bool red = false, blue = false;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const uint8_t* p = img->Pixel(x, y);
      red |= x < 32 && p[0] > 150 && p[1] < 60 && p[2] < 60;
      blue |= p[2] > 120 && p[0] < 100;
    }
  EXPECT_TRUE(red);
  EXPECT_TRUE(blue);
}

// Reads a GLB file into its JSON and binary chunks, checking the container.
void ReadGlb(const std::string& path, json& doc, std::string& bin) {
  const std::string data = t::ReadText(path);
  ASSERT_GE(data.size(), 20u);
  auto u32 = [&](size_t at) {
    uint32_t v;
    std::memcpy(&v, data.data() + at, 4);
    return v;
  };
  ASSERT_EQ(u32(0), 0x46546C67u);  // glTF
  ASSERT_EQ(u32(4), 2u);
  ASSERT_EQ(u32(8), data.size());
  const uint32_t json_len = u32(12);
  ASSERT_EQ(u32(16), 0x4E4F534Au);  // JSON
  ASSERT_EQ(json_len % 4, 0u);
  doc = json::parse(data.substr(20, json_len));
  const size_t at = 20 + json_len;
  ASSERT_LE(at + 8, data.size());
  const uint32_t bin_len = u32(at);
  ASSERT_EQ(u32(at + 4), 0x004E4942u);  // BIN
  ASSERT_EQ(at + 8 + bin_len, data.size());
  bin = data.substr(at + 8, bin_len);
}

TEST(Gltf, StructureAndAnimationAreConsistent) {
  Still s("samples/pendulum.al", 0.0);
  ASSERT_TRUE(s.run.ok);
  const std::string path = t::ScratchDir("gltf") + "/p.glb";
  const auto times = s.sampler->FrameTimes();
  std::string error;
  ASSERT_TRUE(WriteGltf(path, s.scene, times, &error)) << error;
  json doc;
  std::string bin;
  ASSERT_NO_FATAL_FAILURE(ReadGlb(path, doc, bin));
  EXPECT_EQ(doc["asset"]["version"], "2.0");
  ASSERT_EQ(doc["buffers"].size(), 1u);
  EXPECT_EQ(doc["buffers"][0]["byteLength"], bin.size());
  EXPECT_FALSE(doc["buffers"][0].contains("uri"));
  for (const auto& v : doc["bufferViews"]) {
    EXPECT_EQ(v["buffer"], 0);
    EXPECT_LE(v["byteOffset"].get<size_t>() + v["byteLength"].get<size_t>(), bin.size());
    EXPECT_EQ(v["byteOffset"].get<size_t>() % 4, 0u);
  }
  const std::map<std::string, size_t> width = {{"SCALAR", 1}, {"VEC3", 3}, {"VEC4", 4}};
  const auto& accessors = doc["accessors"];
  for (const auto& a : accessors) {
    const auto& v = doc["bufferViews"][a["bufferView"].get<size_t>()];
    EXPECT_LE(a["count"].get<size_t>() * width.at(a["type"]) * 4, v["byteLength"].get<size_t>());
  }
  auto floats = [&](size_t accessor) {
    const auto& a = accessors[accessor];
    const auto& v = doc["bufferViews"][a["bufferView"].get<size_t>()];
    std::vector<float> out(a["count"].get<size_t>() * width.at(a["type"]));
    std::memcpy(out.data(), bin.data() + v["byteOffset"].get<size_t>(), out.size() * 4);
    return out;
  };
  // Meshes: one per body; indices within their vertex count; POSITION bounds.
  ASSERT_EQ(doc["meshes"].size(), 3u);
  for (const auto& mesh : doc["meshes"])
    for (const auto& prim : mesh["primitives"]) {
      const size_t pos = prim["attributes"]["POSITION"];
      EXPECT_TRUE(accessors[pos].contains("min"));
      const size_t n = accessors[pos]["count"];
      EXPECT_EQ(accessors[prim["attributes"]["NORMAL"].get<size_t>()]["count"], n);
      const auto& ia = accessors[prim["indices"].get<size_t>()];
      EXPECT_EQ(ia["componentType"], 5125);
      std::vector<uint32_t> idx(ia["count"].get<size_t>());
      std::memcpy(
          idx.data(),
          bin.data() +
              doc["bufferViews"][ia["bufferView"].get<size_t>()]["byteOffset"].get<size_t>(),
          idx.size() * 4);
      for (uint32_t i : idx) EXPECT_LT(i, n);
      EXPECT_LT(prim["material"].get<size_t>(), doc["materials"].size());
    }
  // Animation: a translation and a rotation channel per moving body; times
  // start at 0 and increase; outputs have one value per time.
  ASSERT_EQ(doc["animations"].size(), 1u);
  const auto& anim = doc["animations"][0];
  EXPECT_EQ(anim["channels"].size(), 6u);
  for (const auto& ch : anim["channels"]) {
    const auto& sampler = anim["samplers"][ch["sampler"].get<size_t>()];
    const size_t node = ch["target"]["node"];
    ASSERT_LT(node, doc["nodes"].size());
    const auto input = floats(sampler["input"]);
    ASSERT_EQ(input.size(), times.size());
    EXPECT_EQ(input.front(), 0.0f);
    for (size_t k = 1; k < input.size(); ++k) EXPECT_GT(input[k], input[k - 1]);
    EXPECT_NEAR(input.back(), 5.0f, 1e-6);
    const auto& in_acc = accessors[sampler["input"].get<size_t>()];
    EXPECT_EQ(in_acc["min"][0], 0.0);
    const auto output = floats(sampler["output"]);
    const std::string path_name = ch["target"]["path"];
    const size_t w = path_name == "rotation" ? 4 : 3;
    ASSERT_EQ(output.size(), w * input.size());
    if (path_name == "rotation")
      for (size_t k = 0; k < input.size(); ++k) {
        const double norm = std::hypot(std::hypot(output[4 * k], output[4 * k + 1]),
                                       std::hypot(output[4 * k + 2], output[4 * k + 3]));
        EXPECT_NEAR(norm, 1.0, 1e-5);
      }
    // The last translation is the simulated end position.
    if (path_name == "translation") {
      const auto end = s.sampler->Poses(5.0)[node].p;
      EXPECT_NEAR(output[output.size() - 3], end.x(), 1e-3 * (1 + std::abs(end.x())));
    }
  }
  // The camera node and the light extension.
  EXPECT_EQ(doc["cameras"].size(), 1u);
  EXPECT_EQ(doc["extensions"]["KHR_lights_punctual"]["lights"].size(), 1u);
}

// Runs asgard with `args`; returns the exit status, output in `out`.
int Asgard(const std::string& args, std::string* out = nullptr) {
  // One log per test: ctest runs tests in parallel processes.
  const std::string log = std::string(ASGARD_BINARY_DIR) + "/render-test-output/asgard-" +
                          ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".log";
  const int rc = t::Run("'" + kAsgard + "' " + args + " > '" + log + "' 2>&1");
  if (out) *out = t::ReadText(log);
  return rc;
}

TEST(Movie, PendulumMp4HasEveryFrame) {
  if (!t::HaveProgram("ffmpeg") || !t::HaveProgram("ffprobe"))
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string dir = t::ScratchDir("movie");
  std::string out;
  ASSERT_EQ(Asgard("render '" + t::SourcePath("samples/pendulum.al") +
                       "' --size 160x120 --quiet -o '" + dir + "/p.mp4'",
                   &out),
            0)
      << out;
  ASSERT_EQ(t::Run("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                   "stream=codec_name,nb_read_frames,duration,width,height -of json '" +
                   dir + "/p.mp4' > '" + dir + "/probe.json'"),
            0);
  const json probe = json::parse(t::ReadText(dir + "/probe.json"));
  const auto& st = probe["streams"][0];
  EXPECT_EQ(st["codec_name"], "h264");
  EXPECT_EQ(st["width"], 160);
  EXPECT_EQ(std::stoi(st["nb_read_frames"].get<std::string>()), 151);  // 0..5 s at 30 per second
  EXPECT_NEAR(std::stod(st["duration"].get<std::string>()), 151 / 30.0, 1e-3);
}

TEST(Movie, WebmAndGif) {
  if (!t::HaveProgram("ffmpeg") || !t::HaveProgram("ffprobe"))
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string dir = t::ScratchDir("movie2");
  const std::string scene = t::SourcePath("tests/render/scenes/colours.al");
  for (const char* ext : {"webm", "gif"}) {
    std::string out;
    ASSERT_EQ(
        Asgard("render '" + scene + "' --size 65x49 --quiet -o '" + dir + "/c." + ext + "'", &out),
        0)
        << out;
    ASSERT_EQ(
        t::Run("ffprobe -v error -count_frames -show_entries stream=codec_name,nb_read_frames -of "
               "csv=p=0 '" +
               dir + "/c." + ext + "' > '" + dir + "/probe.txt'"),
        0);
    const std::string probe = t::ReadText(dir + "/probe.txt");
    EXPECT_EQ(probe, std::string(ext[0] == 'w' ? "vp9" : "gif") + ",11\n") << ext;
  }
}

TEST(RenderCli, RenderUsageAndFailures) {
  const std::string scene = "'" + t::SourcePath("tests/render/scenes/colours.al") + "'";
  const std::string dir = t::ScratchDir("cli");
  std::string out;
  EXPECT_EQ(Asgard("render --help", &out), 0);
  EXPECT_NE(out.find("Usage: asgard render"), std::string::npos);
  EXPECT_EQ(Asgard("export --help"), 0);
  EXPECT_EQ(Asgard("render " + scene, &out), 2);
  EXPECT_NE(out.find("-o OUT is required"), std::string::npos);
  EXPECT_EQ(Asgard("render " + scene + " -o x.bmp"), 2);
  EXPECT_EQ(Asgard("render " + scene + " --style shaded -o '" + dir + "/x.svg'"), 2);
  EXPECT_EQ(Asgard("render " + scene + " --size 10 -o '" + dir + "/x.png'"), 2);
  EXPECT_EQ(Asgard("render " + scene + " --frames 0:1 -o '" + dir + "/x.png'"), 2);
  EXPECT_EQ(Asgard("render " + scene + " -t 7 -o '" + dir + "/x.png'", &out), 2);
  EXPECT_NE(out.find("within the simulated time"), std::string::npos);
  EXPECT_EQ(Asgard("render " + scene + " --view nope -o '" + dir + "/x.png'"), 2);
  EXPECT_EQ(Asgard("render " + scene + " --bogus -o '" + dir + "/x.png'"), 2);
  EXPECT_EQ(Asgard("render " + scene + " --follow nobody -o '" + dir + "/x.png'", &out), 2);
  EXPECT_NE(out.find("no body 'nobody'"), std::string::npos);
  EXPECT_EQ(Asgard("render /nonexistent.al -o '" + dir + "/x.png'"), 1);
  EXPECT_EQ(Asgard("render " + scene + " -o /nonexistent/dir/x.png", &out), 1);
  EXPECT_NE(out.find("cannot write"), std::string::npos);
  EXPECT_EQ(Asgard("export " + scene + " -o '" + dir + "/x.txt'"), 2);
  EXPECT_EQ(Asgard("export " + scene + " --format vrml -o '" + dir + "/x.wrl'"), 2);
}

TEST(RenderCli, NumberedFramesAndStills) {
  const std::string scene = "'" + t::SourcePath("tests/render/scenes/colours.al") + "'";
  const std::string dir = t::ScratchDir("cli2");
  std::string out;
  ASSERT_EQ(
      Asgard("render " + scene + " --frames 0:1:3 --size 32x24 --style wire -o '" + dir + "/f.png'",
             &out),
      0)
      << out;
  EXPECT_NE(out.find("wrote 3 frames"), std::string::npos) << out;
  for (int k = 0; k < 3; ++k) {
    const auto img = render::ReadPng(dir + "/f_000" + std::to_string(k) + ".png");
    ASSERT_TRUE(img);
    EXPECT_EQ(img->width, 32);
  }
  ASSERT_EQ(Asgard("render " + scene +
                       " -t 0.5 --size 32x24 --overlay all --rot 10,20,0 --scale 1.5 -o '" + dir +
                       "/s.ppm'",
                   &out),
            0)
      << out;
  EXPECT_EQ(t::ReadText(dir + "/s.ppm").substr(0, 9), "P6\n32 24\n");
  ASSERT_EQ(Asgard("render " + scene + " --frames 0:1:2 --follow b1 --size 32x24 -o '" + dir +
                       "/follow.pdf'",
                   &out),
            0)
      << out;
  ASSERT_EQ(Asgard("export " + scene + " -t 0.25 -o '" + dir + "/s.pov'", &out), 0) << out;
  ASSERT_EQ(Asgard("export " + scene + " --format rayshade -o '" + dir + "/s.ray'", &out), 0)
      << out;
  ASSERT_EQ(Asgard("export " + scene + " --frames 0:1:5 -o '" + dir + "/s.glb'", &out), 0) << out;
  EXPECT_NE(out.find("5 animation samples"), std::string::npos) << out;
}

// A view element with -follow keeps the followed body at the centre of every
// frame while the rest of the scene moves past; so do views whose -pos is an
// expression of the body's state (seed 4.1.7: the point looked at is
// c − Rᵀ·pos = the body) or of time (the ball is at (4t, 3, 0)).  Two frames
// of one run (--frames) each.
TEST(Cli, ViewFollowKeepsTheBodyCentred) {
  const std::string dir = t::ScratchDir("follow");
  const std::string scene = dir + "/follow.al";
  {
    std::ofstream out(scene);
    out << "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n"
           "shape_set floor -desc {-sub {-box {40 0.2 4}}}\n"
           "body b -shape ball -init_pos {0 3 0} -init_dpos {4 0 0} -color red\n"
           "body f -shape floor -static 1 -init_pos {10 -0.1 0} -color gray\n"
           "view cam -follow b -scale 3 -rot {0 0 0}\n"
           "view state -center {0 0 0} -scale 3 -rot {0 0 0} -pos {{-b.x} {-b.y} {-b.z}}\n"
           "view clock -center {0 0 0} -scale 3 -rot {0 0 0} -pos {{-4 * t} -3 0}\n"
           "simulator -finish 3\n";
  }
  for (const char* view : {"cam", "state", "clock"}) {
    const std::string png = dir + "/" + view + ".png";
    ASSERT_EQ(Asgard("render '" + scene + "' --view " + view +
                     " --frames 0.5:2.5:2 --size 160x120 -o '" + png + "'"),
              0);
    for (int frame = 0; frame < 2; ++frame) {
      const auto img = render::ReadPng(FramePath(png, frame, 2));
      ASSERT_TRUE(img.has_value()) << view << " frame " << frame;
      // Centroid of the red pixels.
      double sx = 0, sy = 0, n = 0;
      for (int y = 0; y < img->height; ++y)
        for (int x = 0; x < img->width; ++x) {
          const uint8_t* p = img->Pixel(x, y);
          if (p[0] > 150 && p[1] < 90 && p[2] < 90) {
            sx += x;
            sy += y;
            ++n;
          }
        }
      ASSERT_GT(n, 10) << "no ball in " << view << " frame " << frame;
      EXPECT_NEAR(sx / n, 80, 2) << view << " frame " << frame;
      EXPECT_NEAR(sy / n, 60, 2) << view << " frame " << frame;
    }
  }
}

}  // namespace
}  // namespace asgard::formats
