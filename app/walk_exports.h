// Avenues — what the walkthrough writes on request: F2 the picture as shown (PNG), F3 the
// hidden-line drawing (SVG) and F4 a stereo pair, through `avenues view -o`'s own code, as
// OUT_DIR/<plan>-NNNN.<ext> numbered past what is there; K appends a keyframe that
// `avenues path --keys` follows. Each returns the message the status line shows, and
// throws std::runtime_error when it cannot write.
#pragma once

#include <string>
#include <vector>

#include "app/commands.h"
#include "render/raster.h"

namespace avenues::app {

class WalkExports {
 public:
  /// Into opt.out_dir; keyframes to opt.record, else OUT_DIR/<plan>-keys.txt.
  WalkExports(const LoadedPlan& plan, const WalkOptions& opt);

  /// The picture as shown.
  std::string picture(const Image& frame);
  /// The view through `avenues view -o`: a drawing (".svg") or, with `stereo` ("parallel",
  /// "pair"), a stereo picture or pair of drawings.
  std::string view(const ViewSetup& v, const std::string& ext, const std::string& stereo);
  /// A keyframe: the eye and the point it looks at.
  std::string keyframe(Vec3 eye, Vec3 look);

  const std::string& keyframe_file() const { return record_path_; }
  int keyframes() const { return keyframes_; }

 private:
  /// OUT_DIR/<plan>-NNNN: the first number from the last one on that none of BASE<suffix> uses.
  std::string next(const std::vector<std::string>& suffixes);

  const LoadedPlan& plan_;
  const WalkOptions& opt_;
  std::string record_path_;
  int keyframes_ = 0, number_ = 1;
};

}  // namespace avenues::app
