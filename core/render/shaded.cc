// OSMesa shaded renderer.
//
// Design: legacy OpenGL (fixed-function lighting, vertex arrays) is what
// Debian 12's OSMesa offers without a window system, and it is all this needs:
// per-vertex Blinn–Phong with up to 8 lights, a 24-bit depth buffer and back-
// face culling (hull faces are counter-clockwise from outside).  There is no
// multisampling in OSMesa, so antialiasing renders at k× the size into our
// own RGBA buffer and reduces it with an integer box filter.  Meshes are
// tessellated once per sampler and drawn in body coordinates under the body's
// pose matrix.  Pure black surfaces are lifted to a dark grey so that shading
// still shows their form (the seed's pendulum is black).
#include "core/render/shaded.h"

#include <GL/gl.h>
#include <GL/osmesa.h>

#include <algorithm>

#include "core/render/mesh.h"

namespace asgard::render {

struct ShadedRenderer::Impl {
  OSMesaContext context = nullptr;
  int width = 0, height = 0, factor = 1;
  ShadedStyle style;
  std::vector<uint8_t> buffer;  // RGBA, bottom row first
  // Mesh cache: valid for the sampler whose bodies vector it was built from.
  const void* cached_for = nullptr;
  size_t cached_count = 0;
  struct PieceDraw {
    Mesh mesh;
    Rgb color;
  };
  std::vector<std::vector<PieceDraw>> meshes;

  ~Impl() {
    if (context) OSMesaDestroyContext(context);
  }

  void Prepare(const SceneSampler& sampler) {
    const auto& bodies = sampler.bodies();
    if (cached_for == bodies.data() && cached_count == bodies.size() && !meshes.empty()) return;
    meshes.clear();
    for (const auto& b : bodies) {
      std::vector<PieceDraw> draws;
      for (const auto& p : b.pieces) {
        draws.push_back({PieceMesh(p, style.sphere_slices), SurfaceColor(p.rgb)});
      }
      meshes.push_back(std::move(draws));
    }
    cached_for = bodies.data();
    cached_count = bodies.size();
  }
};

ShadedRenderer::ShadedRenderer(int width, int height, const ShadedStyle& style)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.style = style;
  m.factor = std::clamp(style.supersample, 1, 4);
  m.width = std::max(1, width);
  m.height = std::max(1, height);
  m.context = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  if (!m.context) {
    error_ = "OSMesa could not create an OpenGL context";
    return;
  }
  m.buffer.assign(static_cast<size_t>(m.width) * m.factor * m.height * m.factor * 4, 0);
  if (!OSMesaMakeCurrent(m.context, m.buffer.data(), GL_UNSIGNED_BYTE, m.width * m.factor,
                         m.height * m.factor)) {
    error_ = "OSMesa could not use a " + std::to_string(m.width * m.factor) + "x" +
             std::to_string(m.height * m.factor) + " buffer";
    OSMesaDestroyContext(m.context);
    m.context = nullptr;
  }
}

ShadedRenderer::~ShadedRenderer() = default;

bool ShadedRenderer::ok() const { return impl_->context != nullptr; }

Image ShadedRenderer::Render(const SceneSampler& sampler, const std::vector<Pose>& poses,
                             const Camera& camera, const std::vector<Light>& lights) {
  Impl& m = *impl_;
  if (!m.context) return Image(m.width, m.height);
  const int W = m.width * m.factor, H = m.height * m.factor;
  OSMesaMakeCurrent(m.context, m.buffer.data(), GL_UNSIGNED_BYTE, W, H);
  m.Prepare(sampler);

  glViewport(0, 0, W, H);
  const Rgb bg = m.style.background;
  glClearColor(static_cast<float>(bg.r), static_cast<float>(bg.g), static_cast<float>(bg.b), 1.f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glShadeModel(GL_SMOOTH);
  glEnable(GL_NORMALIZE);
  glEnable(GL_LIGHTING);
  glEnable(GL_COLOR_MATERIAL);
  glColorMaterial(GL_FRONT, GL_AMBIENT_AND_DIFFUSE);
  const float spec[] = {0.3f, 0.3f, 0.3f, 1.f};
  glMaterialfv(GL_FRONT, GL_SPECULAR, spec);
  glMaterialf(GL_FRONT, GL_SHININESS, 40.f);
  const float amb = static_cast<float>(m.style.ambient);
  const float model_ambient[] = {amb, amb, amb, 1.f};
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, model_ambient);
  glLightModeli(GL_LIGHT_MODEL_LOCAL_VIEWER, GL_TRUE);

  glMatrixMode(GL_PROJECTION);
  const Eigen::Matrix4d proj = camera.ProjectionMatrix();
  glLoadMatrixd(proj.data());
  glMatrixMode(GL_MODELVIEW);
  const Eigen::Matrix4d view = camera.ViewMatrix();
  glLoadMatrixd(view.data());

  // Lights are given in world coordinates: set them under the view matrix.
  std::vector<Light> use = lights;
  if (use.empty()) use.push_back(DefaultLight(camera));
  for (int i = 0; i < 8; ++i) {
    const GLenum id = GL_LIGHT0 + i;
    if (i >= static_cast<int>(use.size())) {
      glDisable(id);
      continue;
    }
    const Light& l = use[i];
    glEnable(id);
    const float k = static_cast<float>(l.intensity);
    const float diffuse[] = {k * float(l.color.r), k * float(l.color.g), k * float(l.color.b), 1.f};
    const float zero[] = {0, 0, 0, 1};
    glLightfv(id, GL_AMBIENT, zero);
    glLightfv(id, GL_DIFFUSE, diffuse);
    glLightfv(id, GL_SPECULAR, diffuse);
    float pos[4];
    if (l.directional) {  // GL wants the direction towards the light
      pos[0] = -float(l.direction.x()), pos[1] = -float(l.direction.y());
      pos[2] = -float(l.direction.z()), pos[3] = 0.f;
    } else {
      pos[0] = float(l.position.x()), pos[1] = float(l.position.y());
      pos[2] = float(l.position.z()), pos[3] = 1.f;
    }
    glLightfv(id, GL_POSITION, pos);
  }

  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  for (size_t b = 0; b < m.meshes.size() && b < poses.size(); ++b) {
    glPushMatrix();
    const Eigen::Matrix4d model = poses[b].Matrix();
    glMultMatrixd(model.data());
    for (const auto& draw : m.meshes[b]) {
      if (draw.mesh.indices.empty()) continue;
      glColor3d(draw.color.r, draw.color.g, draw.color.b);
      glVertexPointer(3, GL_FLOAT, sizeof(Eigen::Vector3f), draw.mesh.positions.data());
      glNormalPointer(GL_FLOAT, sizeof(Eigen::Vector3f), draw.mesh.normals.data());
      glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(draw.mesh.indices.size()), GL_UNSIGNED_INT,
                     draw.mesh.indices.data());
    }
    glPopMatrix();
  }
  glDisableClientState(GL_NORMAL_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
  glFinish();
  return DownsampleRgba(m.buffer.data(), W, H, m.factor, true);
}

}  // namespace asgard::render
