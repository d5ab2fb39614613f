// Movies through the ffmpeg program, and frame-file names.
//
// Design: frames are rendered by Asgard and streamed to `ffmpeg` as raw RGB on
// a pipe (no temporary image files, no codec library linked in).  ffmpeg is
// started with posix_spawnp and an argument vector — no shell, so file names
// need no quoting — with its messages sent to a temporary log that becomes
// the error text if it fails.  SIGPIPE is ignored while writing so a dying
// encoder is reported, not fatal.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "formats/document/file.h"
#include "formats/export/export.h"

extern char** environ;

namespace asgard::formats {

using document::Extension;

bool MovieWriter::IsMovie(const std::string& path) {
  const std::string ext = Extension(path);
  return ext == "mp4" || ext == "webm" || ext == "gif";
}

MovieWriter::~MovieWriter() {
  if (pipe_) Finish();
}

bool MovieWriter::Open(const std::string& path, int width, int height, double fps) {
  const std::string ext = Extension(path);
  if (!IsMovie(path)) {
    error_ = "not a movie file name (.mp4, .webm, .gif): '" + path + "'";
    return false;
  }
  width_ = width, height_ = height, path_ = path;
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  std::vector<std::string> args = {
      "ffmpeg",   "-hide_banner", "-nostdin", "-loglevel",
      "error",    "-y",           "-f",       "rawvideo",
      "-pix_fmt", "rgb24",        "-s",       std::to_string(width) + "x" + std::to_string(height),
      "-r",       rate,           "-i",       "-"};
  const char* even = "pad=ceil(iw/2)*2:ceil(ih/2)*2";
  if (ext == "mp4") {
    args.insert(args.end(), {"-vf", even, "-c:v", "libx264", "-preset", "medium", "-crf", "18",
                             "-pix_fmt", "yuv420p", "-movflags", "+faststart"});
  } else if (ext == "webm") {
    args.insert(args.end(),
                {"-vf", even, "-c:v", "libvpx-vp9", "-b:v", "0", "-crf", "32", "-deadline", "good",
                 "-cpu-used", "4", "-row-mt", "1", "-pix_fmt", "yuv420p"});
  } else {
    args.insert(args.end(),
                {"-filter_complex",
                 "split[a][b];[a]palettegen=stats_mode=full[p];[b][p]paletteuse=dither=bayer",
                 "-loop", "0"});
  }
  args.insert(args.end(), {"-f", ext == "mp4" ? "mp4" : ext, path});

  char log_template[] = "/tmp/asgard-ffmpeg-XXXXXX";
  const int log_fd = mkstemp(log_template);
  if (log_fd >= 0) {
    log_path_ = log_template;
    close(log_fd);
  }
  int fds[2];
  if (pipe(fds) != 0) {
    error_ = "cannot create a pipe for ffmpeg";
    return false;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  posix_spawn_file_actions_addclose(&actions, fds[1]);
  if (!log_path_.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log_path_.c_str(),
                                     O_WRONLY | O_APPEND, 0600);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log_path_.c_str(),
                                     O_WRONLY | O_APPEND, 0600);
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[0]);
  if (rc != 0) {
    close(fds[1]);
    error_ = "cannot run ffmpeg (is it installed?)";
    return false;
  }
  pid_ = pid;
  pipe_ = fdopen(fds[1], "wb");
  return pipe_ != nullptr;
}

bool MovieWriter::AddFrame(const render::Image& frame) {
  if (!pipe_) return false;
  if (frame.width != width_ || frame.height != height_) {
    error_ = "frame size differs from the movie's";
    return false;
  }
  auto* old = std::signal(SIGPIPE, SIG_IGN);
  const bool ok = std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_) == frame.rgb.size();
  std::signal(SIGPIPE, old);
  if (!ok) error_ = "ffmpeg stopped reading frames";
  return ok;
}

bool MovieWriter::Finish() {
  if (!pipe_) return false;
  auto* old = std::signal(SIGPIPE, SIG_IGN);
  std::fclose(pipe_);
  std::signal(SIGPIPE, old);
  pipe_ = nullptr;
  int status = 0;
  bool ok = false;
  if (pid_ > 0 && waitpid(pid_, &status, 0) == pid_)
    ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  pid_ = -1;
  if (!ok) {
    std::string log;
    if (!log_path_.empty()) {
      std::ifstream in(log_path_);
      std::ostringstream ss;
      ss << in.rdbuf();
      log = ss.str();
      while (!log.empty() && (log.back() == '\n' || log.back() == '\r')) log.pop_back();
    }
    error_ = "ffmpeg failed writing '" + path_ + "'" + (log.empty() ? "" : ": " + log);
  }
  if (!log_path_.empty()) unlink(log_path_.c_str());
  log_path_.clear();
  return ok;
}

std::string FramePath(const std::string& pattern, int index, int count) {
  const size_t pct = pattern.find('%');
  if (pct != std::string::npos) {
    size_t end = pct + 1;
    while (end < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[end]))) ++end;
    if (end < pattern.size() && pattern[end] == 'd') {
      char buf[64];
      std::snprintf(buf, sizeof buf, ("%" + pattern.substr(pct + 1, end - pct)).c_str(), index);
      return pattern.substr(0, pct) + buf + pattern.substr(end + 1);
    }
  }
  int digits = 4;
  for (int c = count - 1; c >= 10000; c /= 10) ++digits;
  char buf[32];
  std::snprintf(buf, sizeof buf, "_%0*d", digits, index);
  const size_t dot = pattern.rfind('.');
  const size_t slash = pattern.rfind('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return pattern + buf;
  return pattern.substr(0, dot) + buf + pattern.substr(dot);
}

}  // namespace asgard::formats
