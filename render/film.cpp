// Avenues — a film: pictures, in order, encoded as one video file (see film.h).
#include "render/film.h"

#include <algorithm>
#include <memory>
#include <stdexcept>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "core/atomic_file.h"

namespace avenues {

struct Film::Impl {
  std::string path;  ///< the film
  std::unique_ptr<PendingTempFile> pending;  ///< where it is written until whole (removed unless committed, and on SIGINT/SIGTERM)
  std::string codec;
  int in_width = 0, in_height = 0, width = 0, height = 0;
  long frames = 0;
  bool finished = false;
  AVFormatContext* format = nullptr;
  AVCodecContext* encoder = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* scaler = nullptr;
  int scaler_channels = 0;  ///< the picture channels `scaler` was made for

  [[noreturn]] void fail(const std::string& what, int av_error = 0) const {
    std::string message = "cannot write the film " + path + ": " + what;
    if (av_error != 0) {
      char text[AV_ERROR_MAX_STRING_SIZE] = {};
      av_strerror(av_error, text, sizeof text);
      message += std::string(": ") + text;
    }
    throw std::runtime_error(message);
  }

  /// Sends one picture to the encoder (nullptr: flush) and writes what comes out.
  void encode(AVFrame* f) {
    int rc = avcodec_send_frame(encoder, f);
    if (rc < 0) fail("the encoder refused a frame", rc);
    for (;;) {
      rc = avcodec_receive_packet(encoder, packet);
      if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return;
      if (rc < 0) fail("the encoder failed", rc);
      av_packet_rescale_ts(packet, encoder->time_base, stream->time_base);
      packet->stream_index = stream->index;
      rc = av_interleaved_write_frame(format, packet);  // takes the packet's data
      if (rc < 0) fail("writing a frame failed", rc);
    }
  }

  void close() {
    sws_freeContext(scaler);
    scaler = nullptr;
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&encoder);
    if (format) {
      if (format->pb) avio_closep(&format->pb);
      avformat_free_context(format);
      format = nullptr;
    }
  }

  ~Impl() { close(); }  // then `pending` removes the temporary file unless it was committed
};

Film::Film(const std::string& path, int width, int height, const FilmOptions& options) : impl_(new Impl) {
  Impl& f = *impl_;
  f.path = path;
  av_log_set_level(AV_LOG_ERROR);  // the encoder's statistics are not for the user
  if (path.empty()) f.fail("empty file name");
  if (width < 2 || height < 2)
    f.fail("a film's pictures are at least 2 x 2 pixels, not " + std::to_string(width) + " x " + std::to_string(height));
  if (!(options.fps > 0)) f.fail("the frame rate must be positive");
  f.in_width = width;
  f.in_height = height;
  f.width = width & ~1;  // yuv420p: even sides
  f.height = height & ~1;

  // The temporary file beside the film, core/atomic_file's (".walk.mp4.tmp-XXXXXX"), so a
  // walk's clean-up knows it for a leftover and a signal removes it; FFmpeg writes it by name.
  try {
    check_output_path(path);
    f.pending = std::make_unique<PendingTempFile>(path);
  } catch (const std::exception& e) {
    f.fail(e.what());
  }
  const std::string& temporary = f.pending->path();

  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  if (!codec) codec = avcodec_find_encoder(AV_CODEC_ID_MPEG4);
  if (!codec) f.fail("the FFmpeg libraries have neither an H.264 nor an MPEG-4 encoder");
  f.codec = avcodec_get_name(codec->id);

  int rc = avformat_alloc_output_context2(&f.format, nullptr, "mp4", temporary.c_str());
  if (rc < 0 || !f.format) f.fail("no MP4 muxer", rc);
  f.stream = avformat_new_stream(f.format, nullptr);
  f.encoder = avcodec_alloc_context3(codec);
  f.frame = av_frame_alloc();
  f.packet = av_packet_alloc();
  if (!f.stream || !f.encoder || !f.frame || !f.packet) f.fail("out of memory");

  AVCodecContext* c = f.encoder;
  c->width = f.width;
  c->height = f.height;
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->time_base = AVRational{1, options.fps};
  c->framerate = AVRational{options.fps, 1};
  c->gop_size = 2 * options.fps;
  c->thread_count = std::max(0, options.threads);
  if (codec->id == AV_CODEC_ID_H264) {
    av_opt_set(c->priv_data, "preset", "medium", 0);  // the `ffmpeg` program's defaults
    av_opt_set(c->priv_data, "crf", "23", 0);
  } else {
    c->flags |= AV_CODEC_FLAG_QSCALE;  // constant quality, about as good as H.264's crf 23
    c->global_quality = FF_QP2LAMBDA * 3;
  }
  if (f.format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  rc = avcodec_open2(c, codec, nullptr);
  if (rc < 0) f.fail("cannot open the " + f.codec + " encoder", rc);
  rc = avcodec_parameters_from_context(f.stream->codecpar, c);
  if (rc < 0) f.fail("cannot set up the video stream", rc);
  f.stream->time_base = c->time_base;

  f.frame->format = c->pix_fmt;
  f.frame->width = c->width;
  f.frame->height = c->height;
  rc = av_frame_get_buffer(f.frame, 0);
  if (rc < 0) f.fail("out of memory for a frame", rc);

  rc = avio_open(&f.format->pb, temporary.c_str(), AVIO_FLAG_WRITE);
  if (rc < 0) f.fail("cannot open " + temporary, rc);
  rc = avformat_write_header(f.format, nullptr);
  if (rc < 0) f.fail("cannot write the MP4 header", rc);
}

Film::~Film() = default;

void Film::add(const Image& picture) {
  Impl& f = *impl_;
  if (f.finished) f.fail("a frame added after the film was finished");
  if (picture.width != f.in_width || picture.height != f.in_height)
    f.fail("frame " + std::to_string(f.frames + 1) + " is " + std::to_string(picture.width) + " x " +
           std::to_string(picture.height) + " pixels, the film " + std::to_string(f.in_width) + " x " +
           std::to_string(f.in_height));
  if (picture.channels != 1 && picture.channels != 3)
    f.fail("frame " + std::to_string(f.frames + 1) + " has " + std::to_string(picture.channels) + " channels");
  if (!f.scaler || f.scaler_channels != picture.channels) {
    sws_freeContext(f.scaler);
    f.scaler = sws_getContext(f.in_width, f.in_height, picture.channels == 1 ? AV_PIX_FMT_GRAY8 : AV_PIX_FMT_RGB24,
                              f.width, f.height, AV_PIX_FMT_YUV420P, SWS_BICUBIC, nullptr, nullptr, nullptr);
    if (!f.scaler) f.fail("cannot convert the pictures to yuv420p");
    f.scaler_channels = picture.channels;
  }
  int rc = av_frame_make_writable(f.frame);  // the encoder may still hold the last one
  if (rc < 0) f.fail("out of memory for a frame", rc);
  const uint8_t* source[1] = {picture.data.data()};
  const int stride[1] = {picture.width * picture.channels};
  sws_scale(f.scaler, source, stride, 0, f.in_height, f.frame->data, f.frame->linesize);
  f.frame->pts = f.frames++;
  f.encode(f.frame);
}

void Film::finish() {
  Impl& f = *impl_;
  if (f.finished) return;
  if (f.frames == 0) f.fail("a film needs at least one frame");
  f.encode(nullptr);
  int rc = av_write_trailer(f.format);
  if (rc < 0) f.fail("cannot finish the MP4", rc);
  rc = avio_closep(&f.format->pb);
  if (rc < 0) f.fail("cannot close " + f.pending->path(), rc);
  try {
    f.pending->commit();
  } catch (const std::exception& e) {
    f.fail(e.what());
  }
  f.finished = true;
  f.close();
}

const std::string& Film::codec() const { return impl_->codec; }
int Film::width() const { return impl_->width; }
int Film::height() const { return impl_->height; }
long Film::frames() const { return impl_->frames; }

}  // namespace avenues
