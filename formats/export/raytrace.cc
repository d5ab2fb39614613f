// Ray-tracer scene files: Rayshade (the seed's off-line output) and POV-Ray.
//
// Design: both files describe one instant in world coordinates — bodies are
// posed at t and written as spheres and polygons (Rayshade `poly`) or
// triangle meshes (POV-Ray `mesh`), one surface per colour — with the camera
// of render::MakeCamera, so a ray-traced picture matches the shaded frame.
// POV-Ray is left-handed; the camera's `right` vector is negated, which
// makes it read our right-handed coordinates without mirroring.  Directional
// lights become parallel lights placed far back along their direction.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "formats/export/export.h"

namespace asgard::formats {

namespace {

using render::Rgb;

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

std::string Triple(const Eigen::Vector3d& v, const char* sep = " ") {
  return Num(v.x()) + sep + Num(v.y()) + sep + Num(v.z());
}

std::string Triple(const Rgb& c, const char* sep = " ") {
  return Num(c.r) + sep + Num(c.g) + sep + Num(c.b);
}

std::vector<render::Light> LightsOf(const StillScene& s) {
  return s.lights.empty() ? std::vector<render::Light>{render::DefaultLight(s.camera)} : s.lights;
}

bool Save(const std::string& path, const std::string& text, std::string* error) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.flush();
  if (!out) {
    if (error) *error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

// Distinct surface colours in order of first use.
std::map<std::string, int> SurfaceIndex(const StillScene& s, std::vector<Rgb>& colors) {
  std::map<std::string, int> index;
  for (const auto& b : s.sampler->bodies())
    for (const auto& p : b.pieces) {
      const std::string key = Triple(p.rgb);
      if (index.emplace(key, static_cast<int>(colors.size())).second) colors.push_back(p.rgb);
    }
  return index;
}

}  // namespace

bool WriteRayshade(const std::string& path, const StillScene& s, std::string* error) {
  std::ostringstream o;
  const auto& cam = s.camera;
  o << "/* Asgard scene at t = " << Num(s.t) << " (Rayshade 4.0 input) */\n";
  o << "screen " << cam.width << " " << cam.height << "\n";
  o << "eyep " << Triple(cam.eye) << "\nlookp " << Triple(cam.target) << "\nup " << Triple(cam.up)
    << "\n";
  o << "fov " << Num(cam.fov_x() * 180 / M_PI) << " " << Num(cam.fov_y * 180 / M_PI) << "\n";
  o << "background " << Triple(s.background) << "\n";
  o << "light 0.2 ambient\n";
  for (const auto& l : LightsOf(s)) {
    const Rgb c{l.color.r * l.intensity, l.color.g * l.intensity, l.color.b * l.intensity};
    if (l.directional)  // Rayshade's vector points towards the light
      o << "light " << Triple(c) << " directional " << Triple(-l.direction) << "\n";
    else
      o << "light " << Triple(c) << " point " << Triple(l.position) << "\n";
  }
  std::vector<Rgb> colors;
  const auto index = SurfaceIndex(s, colors);
  for (size_t i = 0; i < colors.size(); ++i)
    o << "surface s" << i << " ambient " << Triple(render::SurfaceColor(colors[i])) << " diffuse "
      << Triple(render::SurfaceColor(colors[i])) << " specular 0.3 0.3 0.3 specpow 40\n";
  const auto poses = s.sampler->Poses(s.t);
  const auto& bodies = s.sampler->bodies();
  for (size_t b = 0; b < bodies.size(); ++b) {
    o << "/* body " << bodies[b].name << " */\n";
    for (const auto& p : bodies[b].pieces) {
      const std::string surf = "s" + std::to_string(index.at(Triple(p.rgb)));
      if (p.is_sphere) {
        o << "sphere " << surf << " " << Num(p.radius) << " " << Triple(poses[b].Apply(p.center))
          << "\n";
        continue;
      }
      for (const auto& face : p.hull.faces) {
        o << "poly " << surf;
        for (int v : face.vertices) o << "  " << Triple(poses[b].Apply(p.hull.vertices[v]));
        o << "\n";
      }
    }
  }
  return Save(path, o.str(), error);
}

bool WritePovray(const std::string& path, const StillScene& s, std::string* error) {
  std::ostringstream o;
  const auto& cam = s.camera;
  o << "// Asgard scene at t = " << Num(s.t) << " (POV-Ray 3.7)\n";
  o << "// povray +I" << path << " +W" << cam.width << " +H" << cam.height << " +A\n";
  o << "#version 3.7;\n";
  o << "global_settings { assumed_gamma 1.0 ambient_light rgb <1,1,1> }\n";
  o << "background { color srgb <" << Triple(s.background, ", ") << "> }\n";
  o << "camera {\n  perspective\n  location <" << Triple(cam.eye, ", ") << ">\n  sky <"
    << Triple(cam.up, ", ") << ">\n  up <0, 1, 0>\n  right <" << Num(-cam.aspect())
    << ", 0, 0>\n  angle " << Num(cam.fov_x() * 180 / M_PI) << "\n  look_at <"
    << Triple(cam.target, ", ") << ">\n}\n";
  const double far = (cam.eye - cam.target).norm() * 100;
  for (const auto& l : LightsOf(s)) {
    const Rgb c{l.color.r * l.intensity, l.color.g * l.intensity, l.color.b * l.intensity};
    if (l.directional) {
      const Eigen::Vector3d from = cam.target - l.direction * far;
      o << "light_source { <" << Triple(from, ", ") << "> color rgb <" << Triple(c, ", ")
        << "> parallel point_at <" << Triple(cam.target, ", ") << "> }\n";
    } else {
      o << "light_source { <" << Triple(l.position, ", ") << "> color rgb <" << Triple(c, ", ")
        << "> }\n";
    }
  }
  std::vector<Rgb> colors;
  const auto index = SurfaceIndex(s, colors);
  for (size_t i = 0; i < colors.size(); ++i)
    o << "#declare S" << i << " = texture { pigment { color srgb <"
      << Triple(render::SurfaceColor(colors[i]), ", ")
      << "> } finish { ambient 0.2 diffuse 0.75 specular 0.3 roughness 0.02 } }\n";
  const auto poses = s.sampler->Poses(s.t);
  const auto& bodies = s.sampler->bodies();
  for (size_t b = 0; b < bodies.size(); ++b) {
    o << "// body " << bodies[b].name << "\n";
    for (const auto& p : bodies[b].pieces) {
      const std::string tex = "texture { S" + std::to_string(index.at(Triple(p.rgb))) + " }";
      if (p.is_sphere) {
        o << "sphere { <" << Triple(poses[b].Apply(p.center), ", ") << ">, " << Num(p.radius) << " "
          << tex << " }\n";
        continue;
      }
      o << "mesh {\n";
      for (const auto& t : p.hull.triangles) {
        o << "  triangle {";
        for (int k = 0; k < 3; ++k)
          o << (k ? ", <" : " <") << Triple(poses[b].Apply(p.hull.vertices[t[k]]), ", ") << ">";
        o << " }\n";
      }
      o << "  " << tex << "\n}\n";
    }
  }
  return Save(path, o.str(), error);
}

}  // namespace asgard::formats
