// Unit tests of the render module: colours, camera and view state, scene
// sampling and overlays, meshes, image files, determinism of shaded frames.
#include <gtest/gtest.h>

#include <cmath>

#include "core/render/color.h"
#include "core/render/image.h"
#include "core/render/mesh.h"
#include "core/render/sampler.h"
#include "core/render/shaded.h"
#include "core/render/view.h"
#include "core/render/wire.h"
#include "tests/render/test_util.h"

namespace asgard::render {
namespace {

using testing::SimulateFile;

TEST(Color, NamesHexAndTriples) {
  EXPECT_EQ(*ParseColor("black"), (Rgb{0, 0, 0}));
  EXPECT_EQ(*ParseColor("Red"), (Rgb{1, 0, 0}));
  EXPECT_EQ(*ParseColor("light gray"), *ParseColor("lightgrey"));
  const Rgb orange = *ParseColor("#ff8800");
  EXPECT_DOUBLE_EQ(orange.r, 1.0);
  EXPECT_NEAR(orange.g, 136 / 255.0, 1e-12);
  EXPECT_EQ(*ParseColor("#f80"), orange);
  EXPECT_EQ(*ParseColor("1 0.5 0"), (Rgb{1, 0.5, 0}));
  EXPECT_NEAR(ParseColor("255 128 0")->g, 128 / 255.0, 1e-12);
  EXPECT_FALSE(ParseColor("blurple"));
  EXPECT_FALSE(ParseColor("#12345"));
  EXPECT_FALSE(ParseColor("1 2"));
  EXPECT_FALSE(ParseColor(""));
  EXPECT_NE(PaletteColor(0), PaletteColor(1));
  EXPECT_EQ(PaletteColor(0), PaletteColor(8));
  EXPECT_GT(SurfaceColor({0, 0, 0}).Luminance(), 0.1);
  EXPECT_EQ(SurfaceColor({1, 0, 0}), (Rgb{1, 0, 0}));
}

TEST(Camera, CentreProjectsToImageCentreAndSphereFits) {
  ViewState v;
  v.center = Eigen::Vector3d(1, 2, 3);
  v.radius = 5;
  v.rotation = DefaultTilt();
  const Camera cam = MakeCamera(v, 64, 48);
  const Eigen::Vector3d c = cam.Project(v.center);
  EXPECT_NEAR(c.x(), 32, 1e-9);
  EXPECT_NEAR(c.y(), 24, 1e-9);
  EXPECT_NEAR(c.z(), kEyeDistance * 5, 1e-9);
  // Points of the framing sphere stay inside the picture.
  for (int k = 0; k < 200; ++k) {
    const double a = k * 0.7, b = k * 0.31;
    const Eigen::Vector3d dir(std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), std::cos(b));
    const Eigen::Vector3d p = cam.Project(v.center + 5 * dir);
    EXPECT_GE(p.x(), 0);
    EXPECT_LE(p.x(), 64);
    EXPECT_GE(p.y(), 0);
    EXPECT_LE(p.y(), 48);
  }
  // Up in the view is up in the picture; world +x goes right without a tilt.
  v.rotation = Eigen::Quaterniond::Identity();
  const Camera flat = MakeCamera(v, 64, 48);
  EXPECT_LT(flat.Project(v.center + Eigen::Vector3d(0, 1, 0)).y(), 24);
  EXPECT_GT(flat.Project(v.center + Eigen::Vector3d(1, 0, 0)).x(), 32);
  // Scale 2 doubles projected distances (about the centre).
  ViewState z = v;
  z.scale = 2;
  const Camera zoom = MakeCamera(z, 64, 48);
  const Eigen::Vector3d p = v.center + Eigen::Vector3d(1, 0, 0);
  EXPECT_NEAR(zoom.Project(p).x() - 32, 2 * (flat.Project(p).x() - 32), 1e-9);
  // Pan moves the scene: the centre now projects right of the middle.
  z.position = Eigen::Vector3d(1, 0, 0);
  EXPECT_GT(MakeCamera(z, 64, 48).Project(v.center).x(), 32);
}

TEST(Camera, ProjectionMatrixAgreesWithProject) {
  ViewState v;
  v.rotation = DefaultTilt();
  v.radius = 3;
  const Camera cam = MakeCamera(v, 80, 40);
  const Eigen::Vector3d p(0.7, -1.2, 0.4);
  const Eigen::Vector4d clip = cam.ProjectionMatrix() * cam.ViewMatrix() * p.homogeneous();
  const double xn = clip.x() / clip.w(), yn = clip.y() / clip.w();
  const Eigen::Vector3d px = cam.Project(p);
  EXPECT_NEAR((xn + 1) / 2 * 80, px.x(), 1e-9);
  EXPECT_NEAR((1 - yn) / 2 * 40, px.y(), 1e-9);
}

TEST(Sampler, PendulumPosesFramesAndOverlays) {
  const pipeline::Run run = SimulateFile("samples/pendulum.al");
  ASSERT_TRUE(run.ok);
  SceneSampler s(run.scene, *run.equations, *run.simulation);
  ASSERT_EQ(s.bodies().size(), 3u);
  EXPECT_TRUE(s.unknown_colors().empty());
  EXPECT_EQ(s.bodies()[0].pieces[0].rgb, (Rgb{0, 0, 0}));  // -color black faces
  EXPECT_TRUE(s.bodies()[2].pieces[0].is_sphere);
  EXPECT_EQ(s.FrameTimes().size(), 151u);  // 5 s at 30 frames per second, both ends
  EXPECT_DOUBLE_EQ(s.FrameTimes().back(), 5.0);
  // Poses are pipeline::SampleBody's.
  const auto poses = s.Poses(1.25);
  const auto f = pipeline::SampleBody(*run.equations, *run.simulation, 1, 1.25);
  EXPECT_DOUBLE_EQ(poses[1].p.x(), f.p[0]);
  EXPECT_DOUBLE_EQ(poses[1].q.w(), f.q[0]);
  // The bound holds every body at the start, and each body's path until it
  // first strays beyond twice the starting framing radius; the rods swing
  // inside it throughout, the ball leaves it (it is thrown far away).
  const Bound b = s.SceneBound();
  std::vector<bool> strayed(s.bodies().size(), false);
  double start_radius = 0;
  {
    const auto ps = s.Poses(0);
    for (size_t i = 0; i < ps.size(); ++i)
      start_radius = std::max(start_radius, (ps[i].Apply(s.bodies()[i].bound_center) - b.center).norm());
  }
  for (double t : s.FrameTimes()) {
    const auto ps = s.Poses(t);
    for (size_t i = 0; i < ps.size(); ++i) {
      const double reach =
          (ps[i].Apply(s.bodies()[i].bound_center) - b.center).norm() + s.bodies()[i].bound_radius;
      if (reach > b.radius + 1e-9) strayed[i] = true;
      if (i < 2) {
        EXPECT_LE(reach, b.radius + 1e-9) << "rod " << i << " at t=" << t;
      }
    }
  }
  EXPECT_TRUE(strayed[2]);
  EXPECT_GT(start_radius, 0.0);
  // Links: b1's end is held near the origin; b2 hangs from b1.
  const auto links = s.LinkSegments(1.25, poses);
  ASSERT_EQ(links.size(), 2u);
  EXPECT_LT(links[0].b.norm(), 1e-12);
  EXPECT_LT((links[0].a - links[0].b).norm(), 0.1);
  EXPECT_LT((links[1].a - links[1].b).norm(), 0.1);
  // Forces: -10 * mass down, applied at the centres of mass.
  const auto forces = s.ForceVectors(1.25, poses);
  ASSERT_EQ(forces.size(), 2u);
  EXPECT_NEAR((forces[0].b - forces[0].a - Eigen::Vector3d(0, -100, 0)).norm(), 0, 1e-9);
  EXPECT_NEAR((forces[0].a - poses[0].p).norm(), 0, 1e-12);
  const auto paths = s.Paths({0, 1, 2});
  ASSERT_EQ(paths.size(), 3u);
  EXPECT_EQ(paths[0].size(), 3u);
}

TEST(Sampler, ViewElementAndLightsOverrideDefaults) {
  const pipeline::Run run = pipeline::Simulate(R"(simulator -finish 0.5
shape_set ball -desc {-sub {-sphere 1}}
body a -shape ball -color "no such colour"
view main -scale 2 -center {1 2 3}
view side -rot {0 1.5707963267948966 0}
lightsource -type point -pos {1 2 3} -color red -intensity 0.5
)");
  ASSERT_TRUE(run.ok);
  SceneSampler s(run.scene, *run.equations, *run.simulation);
  ASSERT_EQ(s.unknown_colors().size(), 1u);
  EXPECT_EQ(s.bodies()[0].pieces[0].rgb, PaletteColor(0));
  const ViewState last = *s.SceneView();
  EXPECT_NEAR(last.rotation.angularDistance(
                  Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()))),
              0, 1e-9);
  EXPECT_DOUBLE_EQ(last.scale, 1.0);
  const ViewState main = *s.SceneView("main");
  EXPECT_DOUBLE_EQ(main.scale, 2.0);
  EXPECT_EQ(main.center, Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(main.rotation.angularDistance(DefaultTilt()), 0, 1e-12);
  EXPECT_NEAR(main.radius, 1.0, 1e-9);  // the ball's bounding sphere
  EXPECT_FALSE(s.SceneView("nope"));
  const auto lights = s.SceneLights();
  ASSERT_EQ(lights.size(), 1u);
  EXPECT_FALSE(lights[0].directional);
  EXPECT_EQ(lights[0].color, (Rgb{1, 0, 0}));
  EXPECT_DOUBLE_EQ(lights[0].intensity, 0.5);
}

// Every triangle faces away from the piece's centre.
void ExpectOutward(const Mesh& m, const Eigen::Vector3f& inside) {
  ASSERT_EQ(m.indices.size() % 3, 0u);
  ASSERT_FALSE(m.indices.empty());
  for (size_t i = 0; i < m.indices.size(); i += 3) {
    const auto& a = m.positions[m.indices[i]];
    const auto& b = m.positions[m.indices[i + 1]];
    const auto& c = m.positions[m.indices[i + 2]];
    const Eigen::Vector3f n = (b - a).cross(c - a);
    EXPECT_GT(n.dot((a + b + c) / 3 - inside), 0) << "triangle " << i / 3;
    EXPECT_GT(n.dot(m.normals[m.indices[i]]), 0);
  }
}

TEST(Mesh, HullsAndSpheresAreClosedAndOutward) {
  const pipeline::Run run = pipeline::Simulate(R"(simulator -finish 0.1
shape_set s -desc {-sub {-box {2 1 1}} -sub {-pos {3 0 0} -sphere 0.5}}
body a -shape s
)");
  ASSERT_TRUE(run.ok);
  SceneSampler s(run.scene, *run.equations, *run.simulation);
  const auto& pieces = s.bodies()[0].pieces;
  ASSERT_EQ(pieces.size(), 2u);
  const Mesh box = PieceMesh(pieces[0]);
  EXPECT_EQ(box.indices.size(), 36u);  // 6 faces × 2 triangles
  Eigen::Vector3f mid = Eigen::Vector3f::Zero();
  for (const auto& v : pieces[0].hull.vertices)
    mid += v.cast<float>() / pieces[0].hull.vertices.size();
  ExpectOutward(box, mid);
  const Mesh ball = PieceMesh(pieces[1], 16);
  ExpectOutward(ball, pieces[1].center.cast<float>());
  for (size_t i = 0; i < ball.positions.size(); ++i)
    EXPECT_NEAR((ball.positions[i] - pieces[1].center.cast<float>()).norm(), 0.5f, 1e-6f);
}

TEST(Image, PngRoundTripPpmAndDownsample) {
  const std::string dir = testing::ScratchDir("image");
  Image img(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x)
      img.Pixel(x, y)[0] = 50 * x, img.Pixel(x, y)[1] = 80 * y, img.Pixel(x, y)[2] = 7;
  ASSERT_TRUE(WritePng(img, dir + "/a.png"));
  const auto back = ReadPng(dir + "/a.png");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->rgb, img.rgb);
  ASSERT_TRUE(WritePpm(img, dir + "/a.ppm"));
  const std::string ppm = testing::ReadText(dir + "/a.ppm");
  EXPECT_EQ(ppm.substr(0, 11), "P6\n5 3\n255\n");
  EXPECT_EQ(ppm.size(), 11u + 45u);
  std::string error;
  EXPECT_FALSE(WritePng(img, "/nonexistent/dir/a.png", &error));
  EXPECT_NE(error.find("cannot write"), std::string::npos);
  // 2×2 RGBA, bottom-up, reduced by 2: the rounded mean.
  const uint8_t rgba[] = {0, 10, 255, 255, 1, 10, 255, 255, 2, 10, 0, 255, 3, 11, 0, 255};
  const Image small = DownsampleRgba(rgba, 2, 2, 2, true);
  ASSERT_EQ(small.width, 1);
  EXPECT_EQ(small.rgb, (std::vector<uint8_t>{2, 10, 128}));
  const auto d = Compare(img, *back);
  EXPECT_TRUE(d.same_size);
  EXPECT_EQ(d.mean, 0.0);
}

TEST(Shaded, SameInputSamePixels) {
  const pipeline::Run run = SimulateFile("tests/render/scenes/colours.al");
  ASSERT_TRUE(run.ok);
  SceneSampler s(run.scene, *run.equations, *run.simulation);
  const Camera cam = MakeCamera(*s.SceneView(), 96, 64);
  ShadedRenderer r1(96, 64), r2(96, 64);
  ASSERT_TRUE(r1.ok()) << r1.error();
  const auto poses = s.Poses(0.5);
  const Image a = r1.Render(s, poses, cam, s.SceneLights());
  const Image b = r1.Render(s, poses, cam, s.SceneLights());
  const Image c = r2.Render(s, poses, cam, s.SceneLights());
  EXPECT_EQ(a.rgb, b.rgb);
  EXPECT_EQ(a.rgb, c.rgb);
  // The blue ball is blue where its centre projects.
  const Eigen::Vector3d at = cam.Project(poses[1].p);
  const uint8_t* centre = a.Pixel(static_cast<int>(at.x()), static_cast<int>(at.y()));
  EXPECT_GT(centre[2], centre[0] + 40);
}

TEST(Wire, SameInputSamePixelsAndBodiesDrawn) {
  const pipeline::Run run = SimulateFile("tests/render/scenes/colours.al");
  ASSERT_TRUE(run.ok);
  SceneSampler s(run.scene, *run.equations, *run.simulation);
  FrameInput f;
  f.sampler = &s;
  f.t = 0.5;
  f.poses = s.Poses(0.5);
  f.camera = MakeCamera(*s.SceneView(), 96, 64);
  const Image a = RenderWire(f, {}), b = RenderWire(f, {});
  EXPECT_EQ(a.rgb, b.rgb);
  int ink = 0;
  for (size_t i = 0; i < a.rgb.size(); i += 3) ink += a.rgb[i] + a.rgb[i + 1] + a.rgb[i + 2] < 600;
  EXPECT_GT(ink, 100);
  Overlays all;
  all.handles = all.links = all.forces = all.paths = true;
  const auto paths = s.Paths(s.FrameTimes());
  f.paths = &paths;
  const Image c = RenderWire(f, all);
  EXPECT_NE(c.rgb, a.rgb);  // the handles at least
}

}  // namespace
}  // namespace asgard::render
