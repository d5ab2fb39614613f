// Movies for the editor's control panel (issue 13): the scene's current text
// rendered by `asgard render` — the core's own movie export (shaded frames
// piped to ffmpeg, formats::MovieWriter) — into a temporary folder, and the
// file's bytes handed back for the browser to download.
#pragma once

#include <array>
#include <optional>
#include <string>

namespace asgard::serve {

struct MovieRequest {
  std::string format = "mp4";  // mp4, webm or gif
  int width = 640, height = 480;
  std::string view;  // a scene `view` element; else the fields below
  std::optional<std::array<double, 3>> rot_degrees, center, pan;
  std::optional<double> scale;
};

// Runs `asgard` (the CLI) as `asgard render SCENE --size WxH ... -o OUT` on
// `text`; true with the movie's bytes, else false with the error the
// command printed.
bool RenderMovie(const std::string& asgard, const std::string& text, const MovieRequest& request,
                 std::string* bytes, std::string* error);

}  // namespace asgard::serve
