// HTML writer.  Design: text is escaped once here (&, <, >, "); the frame
// data is JSON with only base64 and numbers in it, placed in a
// <script type="application/json"> block (no "</" can occur inside), and the
// player reads it on load.  The player keeps the state on the figure element
// (data-state="playing|paused", data-frame) so tests and users can see it.
#include "host-shim/html.h"

#include <cstdio>
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
    let frame = a.poster, playing = false, startWall = 0, startTime = 0;
    function show(i) {
      frame = Math.max(0, Math.min(images.length - 1, i));
      const im = images[frame];
      const draw = function () { ctx.drawImage(im, 0, 0, canvas.width, canvas.height); };
      if (im.complete && im.naturalWidth) draw(); else im.onload = function () { if (frame === images.indexOf(im)) draw(); };
      fig.dataset.frame = frame;
      if (seek) seek.value = frame;
      if (readout) readout.value = readout.textContent = a.times[frame].toFixed(2) + ' s';
    }
    function indexAt(t) {
      let i = 0;
      while (i + 1 < a.times.length && a.times[i + 1] <= t + 1e-9) i++;
      return i;
    }
    function tick(now) {
      if (!playing) return;
      const span = a.times[a.times.length - 1] - a.times[0];
      let t = startTime + (now - startWall) / 1000;
      if (span > 0 && t > a.times[a.times.length - 1]) {
        t = a.times[0] + ((t - a.times[0]) % span);
        startTime = t; startWall = now;
      }
      show(indexAt(t));
      requestAnimationFrame(tick);
    }
    function play() {
      if (playing || images.length < 2) return;
      playing = true; fig.dataset.state = 'playing'; button.textContent = 'Pause';
      startTime = frame >= images.length - 1 ? a.times[0] : a.times[frame];
      startWall = performance.now();
      requestAnimationFrame(tick);
    }
    function pause() {
      playing = false; fig.dataset.state = 'paused'; if (button) button.textContent = 'Play';
    }
    if (button) button.addEventListener('click', function () { playing ? pause() : play(); });
    if (seek) seek.addEventListener('input', function () {
      show(parseInt(seek.value, 10));
      if (playing) { startTime = a.times[frame]; startWall = performance.now(); }
    });
    fig.asgard = { play: play, pause: pause, show: show };
    fig.dataset.state = 'paused';
    show(a.poster);
  });
})();
)";

void Figure(std::ostringstream& s, int index, const HtmlAnimation& a, bool show_scene) {
  s << "<figure class=\"asgard-animation\" id=\"anim-" << index << "\">\n"
    << "<canvas width=\"" << a.width << "\" height=\"" << a.height << "\" aria-label=\"animation "
    << index << "\"></canvas>\n";
  if (a.live && a.frames.size() > 1) {
    s << "<div class=\"controls\"><button type=\"button\" class=\"play\">Play</button>"
      << "<input type=\"range\" class=\"seek\" min=\"0\" max=\"" << a.frames.size() - 1
      << "\" step=\"1\" value=\"" << a.poster << "\" aria-label=\"seek\">"
      << "<output class=\"time\"></output></div>\n";
  }
  s << "<figcaption>" << Escape(a.caption) << "</figcaption>\n";
  if (show_scene) s << "<pre class=\"scene\">" << Escape(a.scene) << "</pre>\n";
  s << "</figure>\n";
}

}  // namespace

std::string WriteHtml(const std::string& title, const std::vector<Block>& blocks,
                      const std::vector<HtmlAnimation>& animations, bool show_scene) {
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
    s << "]}";
  }
  s << "\n}</script>\n<script>" << kPlayer << "</script>\n</body>\n</html>\n";
  return s.str();
}

}  // namespace asgard::host
