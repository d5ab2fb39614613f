// Cairo line drawings.
//
// Design: geometry is transformed to camera coordinates, clipped against the
// near plane there (so bodies behind or through the eye never produce wild
// lines), then projected to pixels and stroked.  Each hull edge is drawn once
// (edges are collected from the merged faces, so coplanar triangles never
// show their diagonals).  A sphere is drawn as its true perspective outline:
// the circle where the cone from the eye touches the sphere, projected (an
// ellipse off axis).  All outputs — raster, SVG, PDF, PostScript — share the
// same drawing code, and Cairo's rasteriser is deterministic.
#include "core/render/wire.h"

#include <cairo-pdf.h>
#include <cairo-ps.h>
#include <cairo-svg.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

namespace asgard::render {

namespace {

double LineWidth(const FrameInput& f, const WireStyle& s) {
  return s.line_width > 0 ? s.line_width : std::max(1.0, f.camera.width / 480.0);
}

void SetColor(cairo_t* cr, Rgb c) {
  // Very light colours would vanish on the white page: draw them mid grey.
  if (c.Luminance() > 0.85) c = {0.6, 0.6, 0.6};
  cairo_set_source_rgb(cr, c.r, c.g, c.b);
}

// Adds the segment a–b (world) to the current path, clipped to the near plane.
void AddSegment(cairo_t* cr, const Camera& cam, const Eigen::Vector3d& a,
                const Eigen::Vector3d& b) {
  Eigen::Vector3d ca = cam.ToCamera(a), cb = cam.ToCamera(b);
  const double zn = -cam.near;
  if (ca.z() > zn && cb.z() > zn) return;
  if (ca.z() > zn) ca = ca + (cb - ca) * ((zn - ca.z()) / (cb.z() - ca.z()));
  if (cb.z() > zn) cb = cb + (ca - cb) * ((zn - cb.z()) / (ca.z() - cb.z()));
  const Eigen::Vector2d pa = cam.CameraToPixel(ca), pb = cam.CameraToPixel(cb);
  cairo_move_to(cr, pa.x(), pa.y());
  cairo_line_to(cr, pb.x(), pb.y());
}

// The outline of a sphere (world centre c, radius r) as seen from the eye.
bool AddSphereOutline(cairo_t* cr, const Camera& cam, const Eigen::Vector3d& c, double r) {
  const Eigen::Vector3d d = c - cam.eye;
  const double dist = d.norm();
  if (dist <= r * 1.0001) return false;
  const Eigen::Vector3d axis = d / dist;
  // Tangent circle: centre on the axis, radius r·√(d²−r²)/d.
  const Eigen::Vector3d cc = cam.eye + d * (1 - r * r / (dist * dist));
  const double rr = r * std::sqrt(dist * dist - r * r) / dist;
  Eigen::Vector3d u = axis.cross(cam.up);
  if (u.norm() < 1e-9) u = axis.cross(Eigen::Vector3d::UnitX());
  u.normalize();
  const Eigen::Vector3d v = axis.cross(u);
  const int n = 72;
  bool started = false;
  for (int k = 0; k <= n; ++k) {
    const double a = 2 * M_PI * k / n;
    const Eigen::Vector3d p = cc + rr * (std::cos(a) * u + std::sin(a) * v);
    const Eigen::Vector3d pc = cam.ToCamera(p);
    if (pc.z() > -cam.near) return started;
    const Eigen::Vector2d px = cam.CameraToPixel(pc);
    if (!started)
      cairo_move_to(cr, px.x(), px.y());
    else
      cairo_line_to(cr, px.x(), px.y());
    started = true;
  }
  cairo_close_path(cr);
  return true;
}

void DrawBodies(cairo_t* cr, const FrameInput& f, double lw) {
  const auto& bodies = f.sampler->bodies();
  cairo_set_line_width(cr, lw);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (size_t b = 0; b < bodies.size(); ++b) {
    const Pose& pose = f.poses[b];
    for (const auto& piece : bodies[b].pieces) {
      SetColor(cr, piece.rgb);
      if (piece.is_sphere) {
        if (AddSphereOutline(cr, f.camera, pose.Apply(piece.center), piece.radius))
          cairo_stroke(cr);
        cairo_new_path(cr);
        continue;
      }
      std::set<std::pair<int, int>> edges;
      for (const auto& face : piece.hull.faces)
        for (size_t k = 0, n = face.vertices.size(); k < n; ++k) {
          const int a = face.vertices[k], c = face.vertices[(k + 1) % n];
          edges.insert({std::min(a, c), std::max(a, c)});
        }
      std::vector<Eigen::Vector3d> world;
      world.reserve(piece.hull.vertices.size());
      for (const auto& v : piece.hull.vertices) world.push_back(pose.Apply(v));
      for (const auto& [a, c] : edges) AddSegment(cr, f.camera, world[a], world[c]);
      cairo_stroke(cr);
    }
  }
}

// A zigzag between two pixel positions (a spring).
void Zigzag(cairo_t* cr, Eigen::Vector2d a, Eigen::Vector2d b, double amplitude) {
  const Eigen::Vector2d d = b - a;
  const double len = d.norm();
  cairo_move_to(cr, a.x(), a.y());
  if (len > 4 * amplitude) {
    const Eigen::Vector2d t = d / len, n(-t.y(), t.x());
    const int teeth = 10;
    const double lead = 0.1 * len, span = len - 2 * lead;
    cairo_line_to(cr, a.x() + t.x() * lead, a.y() + t.y() * lead);
    for (int k = 0; k < teeth; ++k) {
      const Eigen::Vector2d p =
          a + t * (lead + span * (k + 0.5) / teeth) + n * (k % 2 ? -amplitude : amplitude);
      cairo_line_to(cr, p.x(), p.y());
    }
    cairo_line_to(cr, b.x() - t.x() * lead, b.y() - t.y() * lead);
  }
  cairo_line_to(cr, b.x(), b.y());
}

bool InFront(const Camera& cam, const Eigen::Vector3d& p) {
  return cam.ToCamera(p).z() < -cam.near;
}

Eigen::Vector2d Pixel(const Camera& cam, const Eigen::Vector3d& p) {
  return cam.CameraToPixel(cam.ToCamera(p));
}

}  // namespace

void DrawOverlays(cairo_t* cr, const FrameInput& f, const Overlays& o, const WireStyle& style) {
  const double lw = LineWidth(f, style);
  const Camera& cam = f.camera;
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  if (o.paths && f.paths) {
    cairo_set_source_rgba(cr, 0.25, 0.45, 0.75, 0.8);
    cairo_set_line_width(cr, 0.75 * lw);
    for (const auto& path : *f.paths)
      for (size_t k = 1; k < path.size(); ++k) AddSegment(cr, cam, path[k - 1], path[k]);
    cairo_stroke(cr);
  }
  if (o.links) {
    cairo_set_source_rgb(cr, 0.1, 0.55, 0.2);
    cairo_set_line_width(cr, 0.75 * lw);
    for (const auto& s : f.sampler->LinkSegments(f.t, f.poses)) {
      if (!InFront(cam, s.a) || !InFront(cam, s.b)) continue;
      Zigzag(cr, Pixel(cam, s.a), Pixel(cam, s.b), 2.5 * lw);
    }
    cairo_stroke(cr);
  }
  if (o.forces) {
    const auto forces = f.sampler->ForceVectors(f.t, f.poses);
    double largest = 0;
    for (const auto& s : forces) largest = std::max(largest, (s.b - s.a).norm());
    const double length = style.force_length > 0 ? style.force_length : f.view_radius / 5;
    cairo_set_source_rgb(cr, 0.8, 0.1, 0.1);
    cairo_set_line_width(cr, lw);
    for (const auto& s : forces) {
      if (largest <= 0) break;
      const Eigen::Vector3d tip = s.a + (s.b - s.a) * (length / largest);
      if (!InFront(cam, s.a) || !InFront(cam, tip)) continue;
      const Eigen::Vector2d a = Pixel(cam, s.a), b = Pixel(cam, tip);
      const Eigen::Vector2d d = b - a;
      if (d.norm() < 1e-6) continue;
      cairo_move_to(cr, a.x(), a.y());
      cairo_line_to(cr, b.x(), b.y());
      cairo_stroke(cr);
      const Eigen::Vector2d t = d.normalized(), n(-t.y(), t.x());
      const double head = std::min(6 * lw, 0.4 * d.norm());
      const Eigen::Vector2d l = b - t * head + n * head * 0.45, r = b - t * head - n * head * 0.45;
      cairo_move_to(cr, b.x(), b.y());
      cairo_line_to(cr, l.x(), l.y());
      cairo_line_to(cr, r.x(), r.y());
      cairo_close_path(cr);
      cairo_fill(cr);
    }
  }
  if (o.handles) {
    for (const auto& pose : f.poses) {
      if (!InFront(cam, pose.p)) continue;
      const Eigen::Vector2d p = Pixel(cam, pose.p);
      cairo_new_sub_path(cr);
      cairo_arc(cr, p.x(), p.y(), 2.5 * lw, 0, 2 * M_PI);
      cairo_set_source_rgb(cr, 0.95, 0.55, 0.1);
      cairo_fill_preserve(cr);
      cairo_set_source_rgb(cr, 0.3, 0.15, 0.0);
      cairo_set_line_width(cr, 0.5 * lw);
      cairo_stroke(cr);
    }
  }
}

void DrawWire(cairo_t* cr, const FrameInput& f, const Overlays& o, const WireStyle& style) {
  cairo_save(cr);
  cairo_set_source_rgb(cr, style.background.r, style.background.g, style.background.b);
  cairo_paint(cr);
  DrawBodies(cr, f, LineWidth(f, style));
  DrawOverlays(cr, f, o, style);
  cairo_restore(cr);
}

namespace {

Image FromSurface(cairo_surface_t* s) {
  cairo_surface_flush(s);
  const int w = cairo_image_surface_get_width(s), h = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    const auto* row = reinterpret_cast<const uint32_t*>(data + static_cast<size_t>(y) * stride);
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.Pixel(x, y);
      p[0] = (row[x] >> 16) & 0xff, p[1] = (row[x] >> 8) & 0xff, p[2] = row[x] & 0xff;
    }
  }
  return img;
}

}  // namespace

Image RenderWire(const FrameInput& f, const Overlays& o, const WireStyle& style) {
  cairo_surface_t* s =
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, f.camera.width, f.camera.height);
  cairo_t* cr = cairo_create(s);
  DrawWire(cr, f, o, style);
  cairo_destroy(cr);
  Image img = FromSurface(s);
  cairo_surface_destroy(s);
  return img;
}

void OverlayImage(Image& image, const FrameInput& f, const Overlays& o, const WireStyle& style) {
  if (!o.any()) return;
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height);
  cairo_surface_flush(s);
  const int stride = cairo_image_surface_get_stride(s);
  unsigned char* data = cairo_image_surface_get_data(s);
  for (int y = 0; y < image.height; ++y) {
    auto* row = reinterpret_cast<uint32_t*>(data + static_cast<size_t>(y) * stride);
    for (int x = 0; x < image.width; ++x) {
      const uint8_t* p = image.Pixel(x, y);
      row[x] = 0xff000000u | (uint32_t(p[0]) << 16) | (uint32_t(p[1]) << 8) | p[2];
    }
  }
  cairo_surface_mark_dirty(s);
  cairo_t* cr = cairo_create(s);
  DrawOverlays(cr, f, o, style);
  cairo_destroy(cr);
  image = FromSurface(s);
  cairo_surface_destroy(s);
}

VectorDocument::VectorDocument(const std::string& path, Format format, int width, int height) {
  switch (format) {
    case Format::kSvg:
      surface_ = cairo_svg_surface_create(path.c_str(), width, height);
      break;
    case Format::kPdf:
      surface_ = cairo_pdf_surface_create(path.c_str(), width, height);
      break;
    case Format::kPs:
      surface_ = cairo_ps_surface_create(path.c_str(), width, height);
      break;
  }
  if (cairo_surface_status(surface_) != CAIRO_STATUS_SUCCESS) {
    error_ =
        "cannot write '" + path + "': " + cairo_status_to_string(cairo_surface_status(surface_));
    return;
  }
  if (format == Format::kPs) cairo_ps_surface_set_eps(surface_, false);
  cr_ = cairo_create(surface_);
}

VectorDocument::~VectorDocument() {
  if (cr_) cairo_destroy(cr_);
  if (surface_) cairo_surface_destroy(surface_);
}

bool VectorDocument::ok() const { return cr_ != nullptr; }
std::string VectorDocument::error() const { return error_; }

void VectorDocument::AddPage(const FrameInput& f, const Overlays& o, const WireStyle& style) {
  if (!cr_) return;
  if (pages_ > 0) cairo_show_page(cr_);
  DrawWire(cr_, f, o, style);
  ++pages_;
}

bool VectorDocument::Finish() {
  if (!cr_) return false;
  cairo_show_page(cr_);
  cairo_surface_finish(surface_);
  const cairo_status_t st = cairo_surface_status(surface_);
  cairo_destroy(cr_);
  cr_ = nullptr;
  if (st != CAIRO_STATUS_SUCCESS) {
    error_ = cairo_status_to_string(st);
    return false;
  }
  return true;
}

}  // namespace asgard::render
