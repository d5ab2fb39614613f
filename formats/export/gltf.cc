// glTF 2.0 binary (.glb) export with the simulated motion as animation.
//
// Design: geometry is written once, in body coordinates (origin at the centre
// of mass), so each body is one node whose translation and rotation are
// exactly the simulated pose; the animation then only needs two channels per
// moving body, sampled at the given frame times with LINEAR interpolation
// (slerp for rotations — consecutive quaternions are kept in one hemisphere).
// One binary buffer holds everything, 4-byte aligned; POSITION accessors carry
// min/max as the specification requires.  Colours are converted from sRGB to
// glTF's linear base colour.  The camera and lights (KHR_lights_punctual)
// are nodes too, so a viewer opens the file looking at what `render` shows.
#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/render/mesh.h"
#include "formats/export/export.h"

namespace asgard::formats {

namespace {

using nlohmann::json;

constexpr int kFloat = 5126, kUint = 5125;
constexpr int kArrayBuffer = 34962, kElementBuffer = 34963;

class Builder {
 public:
  // Appends bytes as a new buffer view; returns its index.
  int View(const void* data, size_t bytes, int target) {
    while (bin_.size() % 4) bin_.push_back(0);
    json v = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}};
    if (target) v["target"] = target;
    const auto* p = static_cast<const uint8_t*>(data);
    bin_.insert(bin_.end(), p, p + bytes);
    views_.push_back(v);
    return static_cast<int>(views_.size()) - 1;
  }
  int Accessor(int view, int component, size_t count, const char* type, json min = nullptr,
               json max = nullptr) {
    json a = {{"bufferView", view}, {"componentType", component}, {"count", count}, {"type", type}};
    if (!min.is_null()) a["min"] = min, a["max"] = max;
    accessors_.push_back(a);
    return static_cast<int>(accessors_.size()) - 1;
  }
  int Floats(const std::vector<float>& v, int width, const char* type, int target, bool bounds) {
    const int view = View(v.data(), v.size() * sizeof(float), target);
    json min = nullptr, max = nullptr;
    if (bounds && !v.empty()) {
      std::vector<float> lo(v.begin(), v.begin() + width), hi = lo;
      for (size_t i = 0; i < v.size(); ++i)
        lo[i % width] = std::min(lo[i % width], v[i]),
               hi[i % width] = std::max(hi[i % width], v[i]);
      min = lo, max = hi;
    }
    return Accessor(view, kFloat, v.size() / width, type, min, max);
  }
  std::vector<uint8_t> bin_;
  json views_ = json::array();
  json accessors_ = json::array();
};

double Linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// Quaternion (x y z w) turning −z into `forward` with +y towards `up`.
json LookRotation(const Eigen::Vector3d& forward, const Eigen::Vector3d& up_hint) {
  const Eigen::Vector3d f = forward.normalized();
  Eigen::Vector3d s = f.cross(up_hint);
  if (s.norm() < 1e-9) s = f.cross(Eigen::Vector3d::UnitX());
  s.normalize();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix3d m;
  m.col(0) = s, m.col(1) = u, m.col(2) = -f;
  const Eigen::Quaterniond q(m);
  return {q.x(), q.y(), q.z(), q.w()};
}

}  // namespace

bool WriteGltf(const std::string& path, const StillScene& s, const std::vector<double>& times_in,
               std::string* error) {
  const auto& bodies = s.sampler->bodies();
  Builder b;
  json meshes = json::array(), materials = json::array(), nodes = json::array();
  std::map<std::string, int> material_index;
  const auto poses = s.sampler->Poses(s.t);
  json scene_nodes = json::array();
  for (size_t i = 0; i < bodies.size(); ++i) {
    json prims = json::array();
    for (const auto& piece : bodies[i].pieces) {
      const render::Mesh m = render::PieceMesh(piece, 24);
      if (m.indices.empty()) continue;
      std::vector<float> pos, nrm;
      for (const auto& p : m.positions) pos.insert(pos.end(), {p.x(), p.y(), p.z()});
      for (const auto& n : m.normals) nrm.insert(nrm.end(), {n.x(), n.y(), n.z()});
      const int ap = b.Floats(pos, 3, "VEC3", kArrayBuffer, true);
      const int an = b.Floats(nrm, 3, "VEC3", kArrayBuffer, false);
      const int iv = b.View(m.indices.data(), m.indices.size() * 4, kElementBuffer);
      const int ai = b.Accessor(iv, kUint, m.indices.size(), "SCALAR");
      const render::Rgb c = render::SurfaceColor(piece.rgb);
      const std::string key =
          std::to_string(c.r) + "," + std::to_string(c.g) + "," + std::to_string(c.b);
      auto [it, fresh] = material_index.emplace(key, static_cast<int>(materials.size()));
      if (fresh)
        materials.push_back({{"name", "color" + std::to_string(it->second)},
                             {"pbrMetallicRoughness",
                              {{"baseColorFactor", {Linear(c.r), Linear(c.g), Linear(c.b), 1.0}},
                               {"metallicFactor", 0.0},
                               {"roughnessFactor", 0.55}}}});
      prims.push_back({{"attributes", {{"POSITION", ap}, {"NORMAL", an}}},
                       {"indices", ai},
                       {"material", it->second},
                       {"mode", 4}});
    }
    json node = {{"name", bodies[i].name}};
    const auto& pose = poses[i];
    node["translation"] = {pose.p.x(), pose.p.y(), pose.p.z()};
    node["rotation"] = {pose.q.x(), pose.q.y(), pose.q.z(), pose.q.w()};
    if (!prims.empty()) {
      node["mesh"] = meshes.size();
      meshes.push_back({{"name", bodies[i].name}, {"primitives", prims}});
    }
    scene_nodes.push_back(nodes.size());
    nodes.push_back(node);
  }
  // Camera.
  const auto& cam = s.camera;
  json cameras = json::array({{{"type", "perspective"},
                               {"perspective",
                                {{"yfov", cam.fov_y},
                                 {"aspectRatio", cam.aspect()},
                                 {"znear", cam.near},
                                 {"zfar", cam.far}}}}});
  scene_nodes.push_back(nodes.size());
  nodes.push_back({{"name", "camera"},
                   {"camera", 0},
                   {"translation", {cam.eye.x(), cam.eye.y(), cam.eye.z()}},
                   {"rotation", LookRotation(cam.target - cam.eye, cam.up)}});
  // Lights.
  json lights = json::array();
  const auto use =
      s.lights.empty() ? std::vector<render::Light>{render::DefaultLight(cam)} : s.lights;
  for (const auto& l : use) {
    json node = {{"name", "light" + std::to_string(lights.size())},
                 {"extensions", {{"KHR_lights_punctual", {{"light", lights.size()}}}}}};
    if (l.directional) {
      node["rotation"] = LookRotation(l.direction, cam.up);
      node["translation"] = {cam.target.x(), cam.target.y(), cam.target.z()};
    } else {
      node["translation"] = {l.position.x(), l.position.y(), l.position.z()};
    }
    lights.push_back({{"type", l.directional ? "directional" : "point"},
                      {"color", {l.color.r, l.color.g, l.color.b}},
                      {"intensity", l.directional ? 3.0 * l.intensity : 1000.0 * l.intensity}});
    scene_nodes.push_back(nodes.size());
    nodes.push_back(node);
  }
  // Animation: strictly increasing times only.
  std::vector<double> times;
  for (double t : times_in)
    if (times.empty() || t > times.back()) times.push_back(t);
  json animations = json::array();
  if (times.size() >= 2) {
    std::vector<float> input;
    for (double t : times) input.push_back(static_cast<float>(t - times.front()));
    const int ain = b.Floats(input, 1, "SCALAR", 0, true);
    std::vector<std::vector<render::Pose>> all;
    for (double t : times) all.push_back(s.sampler->Poses(t));
    json samplers = json::array(), channels = json::array();
    for (size_t i = 0; i < bodies.size(); ++i) {
      if (bodies[i].is_static) continue;
      std::vector<float> tr, rot;
      Eigen::Quaterniond prev = all[0][i].q;
      for (const auto& frame : all) {
        const auto& p = frame[i];
        Eigen::Quaterniond q = p.q;
        if (q.coeffs().dot(prev.coeffs()) < 0) q.coeffs() *= -1;
        prev = q;
        tr.insert(tr.end(), {float(p.p.x()), float(p.p.y()), float(p.p.z())});
        rot.insert(rot.end(), {float(q.x()), float(q.y()), float(q.z()), float(q.w())});
      }
      const int at = b.Floats(tr, 3, "VEC3", 0, false);
      const int ar = b.Floats(rot, 4, "VEC4", 0, false);
      for (auto [acc, prop] : {std::pair{at, "translation"}, std::pair{ar, "rotation"}}) {
        channels.push_back(
            {{"sampler", samplers.size()}, {"target", {{"node", i}, {"path", prop}}}});
        samplers.push_back({{"input", ain}, {"output", acc}, {"interpolation", "LINEAR"}});
      }
    }
    if (!channels.empty())
      animations.push_back(
          {{"name", "simulation"}, {"samplers", samplers}, {"channels", channels}});
  }
  while (b.bin_.size() % 4) b.bin_.push_back(0);
  json doc = {{"asset", {{"version", "2.0"}, {"generator", "Asgard"}}},
              {"scene", 0},
              {"scenes", {{{"name", "asgard"}, {"nodes", scene_nodes}}}},
              {"nodes", nodes},
              {"cameras", cameras},
              {"buffers", {{{"byteLength", b.bin_.size()}}}},
              {"bufferViews", b.views_},
              {"accessors", b.accessors_},
              {"extensionsUsed", {"KHR_lights_punctual"}},
              {"extensions", {{"KHR_lights_punctual", {{"lights", lights}}}}}};
  if (!meshes.empty()) doc["meshes"] = meshes;
  if (!materials.empty()) doc["materials"] = materials;
  if (!animations.empty()) doc["animations"] = animations;
  std::string text = doc.dump();
  while (text.size() % 4) text.push_back(' ');
  const bool has_bin = !b.bin_.empty();
  const uint32_t total = 12 + 8 + static_cast<uint32_t>(text.size()) +
                         (has_bin ? 8 + static_cast<uint32_t>(b.bin_.size()) : 0);
  std::ofstream out(path, std::ios::binary);
  auto u32 = [&out](uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
  u32(0x46546C67);  // "glTF"
  u32(2);
  u32(total);
  u32(static_cast<uint32_t>(text.size()));
  u32(0x4E4F534A);  // "JSON"
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (has_bin) {
    u32(static_cast<uint32_t>(b.bin_.size()));
    u32(0x004E4942);  // "BIN\0"
    out.write(reinterpret_cast<const char*>(b.bin_.data()),
              static_cast<std::streamsize>(b.bin_.size()));
  }
  out.flush();
  if (!out) {
    if (error) *error = "cannot write '" + path + "'";
    return false;
  }
  return true;
}

}  // namespace asgard::formats
