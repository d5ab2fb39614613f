// HTML writer.  Design: text is escaped once here (&, <, >, "); the frame
// data is JSON with only base64 and numbers in it, placed in a
// <script type="application/json"> block (no "</" can occur inside), and the
// player reads it on load.  The player keeps the state on the figure element
// (data-state="playing|paused", data-frame) so tests and users can see it.
#include "host-shim/html.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <sstream>

#include "formats/document/file.h"

namespace asgard::host {

namespace {

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

const char* const kStyle = R"(
body { margin: 0; background: #e9eaee; font: 16px/1.5 "DejaVu Serif", Georgia, serif; color: #1a1a1f; }
article { max-width: 42em; margin: 2em auto; background: #fff; padding: 2.5em 3.5em; box-shadow: 0 1px 4px rgba(0,0,0,.15); }
h1, h2 { font-family: "DejaVu Sans", Helvetica, sans-serif; }
h1 { font-size: 1.7em; margin: 0 0 .4em; } h2 { font-size: 1.15em; margin: 1.4em 0 .3em; }
p { margin: .6em 0; text-align: justify; }
p.field { margin: .1em 0; text-align: left; } p.field b { display: inline-block; min-width: 6em; }
hr { border: 0; border-top: 1px solid #999; margin: 1em 0; }
figure.asgard-animation { margin: 1.2em auto; text-align: center; }
figure.asgard-animation canvas { touch-action: none; }
figure.asgard-animation canvas { border: 1px solid #8c919e; background: #f2f2f5; max-width: 100%; }
.controls { display: flex; gap: .6em; align-items: center; justify-content: center; margin: .3em auto 0;
  font: 13px "DejaVu Sans", sans-serif; }
.controls button { min-width: 5em; } .controls input[type=range] { flex: 1; max-width: 20em; }
.controls output { min-width: 5em; text-align: left; font-variant-numeric: tabular-nums; }
figcaption { font: 12px "DejaVu Sans", sans-serif; color: #5a5c66; margin-top: .2em; }
pre.scene { text-align: left; background: #f6f6f8; padding: .8em; overflow: auto; font-size: 13px; }
)";

const char* const kPlayer = R"(
(function () {
  const data = JSON.parse(document.getElementById('asgard-frames').textContent);
  document.querySelectorAll('figure.asgard-animation').forEach(function (fig) {
    const a = data[fig.id];
    const canvas = fig.querySelector('canvas'), ctx = canvas.getContext('2d');
    const button = fig.querySelector('button.play'), seek = fig.querySelector('input.seek');
    const readout = fig.querySelector('output.time');
    if (!a || !a.frames.length) return;
    const images = a.frames.map(function (src) { const im = new Image(); im.src = src; return im; });
    // WebGL when the page has the player and the browser has WebGL: any
    // time, rotatable; otherwise the frames.
    const gl = a.player && window.asgardPlayer ? window.asgardPlayer(fig, canvas, a.player) : null;
    const steps = gl ? gl.times.n : images.length;
    const t0 = gl ? gl.times.t0 : a.times[0], t1 = gl ? gl.times.t1 : a.times[a.times.length - 1];
    function timeOf(i) { return gl ? (steps > 1 ? t0 + (t1 - t0) * i / (steps - 1) : t0) : a.times[i]; }
    function indexAt(t) {
      if (gl) return steps > 1 && t1 > t0 ? Math.round((t - t0) / (t1 - t0) * (steps - 1)) : 0;
      let i = 0;
      while (i + 1 < a.times.length && a.times[i + 1] <= t + 1e-9) i++;
      return i;
    }
    let frame = 0, time = t0, playing = false, startWall = 0, startTime = 0;
    function shown(i, t) {
      frame = i; time = t;
      fig.dataset.frame = frame;
      fig.dataset.time = t.toFixed(6);
      if (seek) seek.value = frame;
      if (readout) readout.value = readout.textContent = t.toFixed(2) + ' s';
    }
    function showTime(t) {
      t = Math.max(t0, Math.min(t1, t));
      if (!gl) return show(indexAt(t));
      gl.draw(t);
      shown(indexAt(t), t);
    }
    function show(i) {
      i = Math.max(0, Math.min(steps - 1, i));
      if (gl) { gl.draw(timeOf(i)); return shown(i, timeOf(i)); }
      const im = images[i];
      const draw = function () { ctx.drawImage(im, 0, 0, canvas.width, canvas.height); };
      if (im.complete && im.naturalWidth) draw(); else im.onload = function () { if (frame === images.indexOf(im)) draw(); };
      shown(i, a.times[i]);
    }
    function tick(now) {
      if (!playing) return;
      let t = startTime + (now - startWall) / 1000;
      if (t1 > t0 && t > t1) {
        t = t0 + ((t - t0) % (t1 - t0));
        startTime = t; startWall = now;
      }
      showTime(t);
      requestAnimationFrame(tick);
    }
    function play() {
      if (playing || steps < 2) return;
      playing = true; fig.dataset.state = 'playing'; button.textContent = 'Pause';
      startTime = time >= t1 ? t0 : time;
      startWall = performance.now();
      requestAnimationFrame(tick);
    }
    function pause() {
      playing = false; fig.dataset.state = 'paused'; if (button) button.textContent = 'Play';
    }
    if (button) button.addEventListener('click', function () { playing ? pause() : play(); });
    if (steps < 2 && fig.querySelector('.controls')) fig.querySelector('.controls').style.display = 'none';
    if (seek) {
      seek.max = String(Math.max(0, steps - 1));
      seek.addEventListener('input', function () {
        show(parseInt(seek.value, 10));
        if (playing) { startTime = time; startWall = performance.now(); }
      });
    }
    fig.asgard = { play: play, pause: pause, show: show, showTime: showTime, webgl: gl };
    fig.dataset.state = 'paused';
    if (gl) showTime(a.times[a.poster]); else show(a.poster);
  });
})();
)";

void Figure(std::ostringstream& s, int index, const HtmlAnimation& a, bool show_scene) {
  s << "<figure class=\"asgard-animation\" id=\"anim-" << index << "\">\n"
    << "<canvas width=\"" << a.width << "\" height=\"" << a.height << "\" aria-label=\"animation "
    << index << "\"></canvas>\n";
  if (a.live && (a.frames.size() > 1 || !a.player.empty())) {
    s << "<div class=\"controls\"><button type=\"button\" class=\"play\">Play</button>"
      << "<input type=\"range\" class=\"seek\" min=\"0\" max=\"" << a.frames.size() - 1
      << "\" step=\"1\" value=\"" << a.poster << "\" aria-label=\"seek\">"
      << "<output class=\"time\"></output></div>\n";
  }
  s << "<figcaption>" << Escape(a.caption) << "</figcaption>\n";
  if (show_scene) s << "<pre class=\"scene\">" << Escape(a.scene) << "</pre>\n";
  s << "</figure>\n";
}

// Little-endian bytes of 32-bit values, for typed arrays in the page.
void PutU32(std::string& out, uint32_t u) {
  for (int k = 0; k < 4; ++k) out.push_back(static_cast<char>((u >> (8 * k)) & 0xff));
}
void PutF32(std::string& out, double v) {
  const float f = static_cast<float>(v);
  uint32_t u = 0;
  std::memcpy(&u, &f, sizeof u);
  PutU32(out, u);
}

}  // namespace

std::string PlayerJson(const std::string& reply, std::string* error) {
  using nlohmann::json;
  const json in = json::parse(reply, nullptr, false);
  auto fail = [&](const std::string& why) {
    if (error) *error = "the player data " + why;
    return std::string();
  };
  if (in.is_discarded() || !in.is_object()) return fail("is not a JSON object");
  try {
    const json& times = in.at("times");
    const json& poses = in.at("poses");
    const json& bodies = in.at("bodies");
    const size_t n = times.size(), nb = bodies.size();
    if (n == 0 || poses.size() != n) return fail("has no frames, or not one pose list per time");
    const double t0 = times.front().get<double>(), t1 = times.back().get<double>();
    for (size_t f = 0; f < n; ++f) {
      const double even = n > 1 ? t0 + (t1 - t0) * static_cast<double>(f) / (n - 1) : t0;
      if (std::fabs(times[f].get<double>() - even) > 1e-6 * (1 + std::fabs(t1 - t0)))
        return fail("has times that are not evenly spaced");
      if (poses[f].size() != 7 * nb) return fail("has a frame without 7 numbers per body");
    }
    // A body moves when any number of its pose differs from its first.
    std::vector<int> track(nb, -1);
    int tracks = 0;
    for (size_t b = 0; b < nb; ++b)
      for (size_t f = 1; f < n && track[b] < 0; ++f)
        for (size_t k = 0; k < 7; ++k)
          if (std::fabs(poses[f][7 * b + k].get<double>() - poses[0][7 * b + k].get<double>()) >
              1e-9) {
            track[b] = tracks++;
            break;
          }
    json out_bodies = json::array();
    for (size_t b = 0; b < nb; ++b) {
      const json& body = bodies[b];
      json pieces = json::array();
      for (const json& p : body.at("pieces")) {
        json piece = {{"color", p.at("color")}};
        if (p.at("sphere").get<bool>()) {
          const json& c = p.at("center");
          piece["sphere"] = {c.at(0), c.at(1), c.at(2), p.at("radius")};
        } else {
          std::string v, i;
          const json& vertices = p.at("vertices");
          const json& triangles = p.at("triangles");
          for (const json& x : vertices) PutF32(v, x.get<double>());
          uint64_t most = 0;
          for (const json& k : triangles) {
            const int64_t index = k.get<int64_t>();
            if (index < 0 || 3 * static_cast<uint64_t>(index) >= vertices.size())
              return fail("has a triangle with a vertex out of range");
            most = std::max<uint64_t>(most, static_cast<uint64_t>(index));
          }
          const bool wide = most > 0xffff;
          for (const json& k : triangles) {
            const auto index = k.get<uint32_t>();
            if (wide) {
              PutU32(i, index);
            } else {
              i.push_back(static_cast<char>(index & 0xff));
              i.push_back(static_cast<char>(index >> 8));
            }
          }
          piece["v"] = document::Base64Encode(v);
          piece["i"] = document::Base64Encode(i);
          if (wide) piece["i32"] = true;
        }
        pieces.push_back(std::move(piece));
      }
      json entry = {{"name", body.at("name")}, {"pieces", std::move(pieces)}};
      if (track[b] >= 0) {
        entry["track"] = track[b];
      } else {
        json pose = json::array();
        for (size_t k = 0; k < 7; ++k) pose.push_back(poses[0][7 * b + k]);
        entry["pose"] = std::move(pose);
      }
      out_bodies.push_back(std::move(entry));
    }
    std::string packed;
    packed.reserve(n * static_cast<size_t>(tracks) * 28);
    for (size_t f = 0; f < n; ++f)
      for (size_t b = 0; b < nb; ++b)
        if (track[b] >= 0)
          for (size_t k = 0; k < 7; ++k) PutF32(packed, poses[f][7 * b + k].get<double>());
    json out = {{"t0", t0},
                {"t1", t1},
                {"n", n},
                {"camera", in.at("camera")},
                {"lights", in.value("lights", json::array())},
                {"bodies", std::move(out_bodies)},
                {"poses", document::Base64Encode(packed)}};
    // Links and force arrows, six numbers each per frame, packed as the
    // poses are (a slave without them leaves them out).
    for (const char* key : {"links", "arrows"}) {
      if (!in.contains(key)) continue;
      const json& frames = in.at(key);
      if (frames.size() != n) return fail(std::string("has not one ") + key + " list per time");
      const size_t count = frames[0].size();
      if (count % 6) return fail(std::string("has ") + key + " without 6 numbers each");
      std::string numbers;
      numbers.reserve(n * count * 4);
      for (const json& frame : frames) {
        if (frame.size() != count) return fail(std::string("has frames with unlike ") + key);
        for (const json& x : frame) PutF32(numbers, x.get<double>());
      }
      out[key] = document::Base64Encode(numbers);
    }
    if (in.contains("arrow_length")) out["arrow_length"] = in.at("arrow_length");
    // A moving view's camera per frame ([eye, target, up]), packed likewise.
    if (in.contains("cameras")) {
      const json& cameras = in.at("cameras");
      if (cameras.size() != n) return fail("has not one camera per time");
      std::string numbers;
      numbers.reserve(n * 36);
      for (const json& camera : cameras) {
        if (camera.size() != 3) return fail("has a camera without its eye, target and up");
        for (const json& v : camera) {
          if (v.size() != 3) return fail("has a camera vector without 3 numbers");
          for (const json& x : v) PutF32(numbers, x.get<double>());
        }
      }
      out["cameras"] = document::Base64Encode(numbers);
    }
    // Inside <script type="application/json">: no "</" may occur.
    std::string text = out.dump();
    for (size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
      text.replace(at, 2, "<\\/");
    return text;
  } catch (const json::exception& e) {
    return fail(std::string("is malformed: ") + e.what());
  }
}

std::string WriteHtml(const std::string& title, const std::vector<Block>& blocks,
                      const std::vector<HtmlAnimation>& animations, bool show_scene,
                      const std::string& player_script) {
  std::ostringstream s;
  s << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<meta name=\"generator\" content=\"dochost (Asgard)\">\n<title>" << Escape(title)
    << "</title>\n<style>" << kStyle << "</style>\n</head>\n<body>\n<article>\n";
  bool in_fields = false;
  for (const Block& b : blocks) {
    if (in_fields && b.kind != Block::kField) s << "<hr>\n";
    in_fields = b.kind == Block::kField;
    switch (b.kind) {
      case Block::kTitle:
        s << "<h1>" << Escape(b.text) << "</h1>\n";
        break;
      case Block::kHeading:
        s << "<h2>" << Escape(b.text) << "</h2>\n";
        break;
      case Block::kField:
        s << "<p class=\"field\"><b>" << Escape(b.label) << ":</b> " << Escape(b.text) << "</p>\n";
        break;
      case Block::kParagraph:
        s << "<p>" << Escape(b.text) << "</p>\n";
        break;
      case Block::kEmbedded:
        if (b.item >= 0 && static_cast<size_t>(b.item) < animations.size())
          Figure(s, b.item + 1, animations[static_cast<size_t>(b.item)], show_scene);
        break;
    }
  }
  s << "</article>\n<script type=\"application/json\" id=\"asgard-frames\">{";
  for (size_t i = 0; i < animations.size(); ++i) {
    const HtmlAnimation& a = animations[i];
    s << (i ? ",\n" : "\n") << "\"anim-" << i + 1 << "\":{\"poster\":" << a.poster
      << ",\"times\":[";
    for (size_t k = 0; k < a.times.size(); ++k) s << (k ? "," : "") << Number(a.times[k]);
    s << "],\"frames\":[";
    for (size_t k = 0; k < a.frames.size(); ++k)
      s << (k ? ",\n" : "\n") << "\"data:image/png;base64," << document::Base64Encode(a.frames[k])
        << "\"";
    s << "]";
    if (!a.player.empty()) s << ",\n\"player\":" << a.player;
    s << "}";
  }
  s << "\n}</script>\n";
  if (!player_script.empty()) s << "<script>" << player_script << "</script>\n";
  s << "<script>" << kPlayer << "</script>\n</body>\n</html>\n";
  return s.str();
}

}  // namespace asgard::host
