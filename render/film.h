// Avenues — a film: pictures, in order, encoded as one video file.
//
// A walk's frames become DIR/walk.mp4 through the FFmpeg libraries themselves (libavcodec,
// libavformat, libswscale), never through a shell or the `ffmpeg` program:
//
//   Film film("walk.mp4", 640, 360);   // a temporary file beside walk.mp4 is opened
//   for (...) film.add(picture);       // each picture the size given, RGB or grey
//   film.finish();                     // flushed, then renamed over walk.mp4
//
// The video is H.264 (libx264) when the FFmpeg libraries have it, else MPEG-4 Part 2, in
// the yuv420p colour format every player reads; as yuv420p halves the chroma in both
// directions, a picture of odd width or height is scaled to the even size just below
// (161 x 91 becomes 160 x 90). A film that is not finished (an exception, a failed frame)
// removes its temporary file: a film is written whole or not at all, like every file
// Avenues writes (core/atomic_file.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/raster.h"

namespace avenues {

struct FilmOptions {
  int fps = 25;     ///< [frames/s] > 0
  int threads = 0;  ///< the encoder's threads; 0: the encoder's own choice (about as many as cores)
};

class Film {
 public:
  /// Opens the film for pictures of width x height pixels (each at least 2). Throws
  /// std::runtime_error naming `path` when no encoder or no temporary file can be had.
  Film(const std::string& path, int width, int height, const FilmOptions& options = {});
  /// Without finish(): the temporary file is removed and `path` is left as it was.
  ~Film();
  Film(const Film&) = delete;
  Film& operator=(const Film&) = delete;

  /// Appends one picture of the film's size (grey or RGB). Throws std::runtime_error.
  void add(const Image& picture);
  /// Flushes the encoder, closes the file and renames it over `path`. Throws
  /// std::runtime_error naming `path`; the temporary file is then removed.
  void finish();

  const std::string& codec() const;  ///< "h264" or "mpeg4"
  int width() const;                 ///< [px] of the video: even
  int height() const;                ///< [px] of the video: even
  long frames() const;               ///< pictures added so far

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace avenues
