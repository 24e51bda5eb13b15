// Avenues — OpenMesh kept quiet while it works (internal to plans/).
#pragma once

#include <OpenMesh/Core/System/omstream.hh>

namespace avenues {

/// OpenMesh talks while it works (a material its OBJ file names but does not define, a
/// face it refuses): not to Avenues' users, who get Avenues' own messages. Quiet while
/// alive. Its streams are global: keep one alive around work on several threads.
class QuietOpenMesh {
 public:
  QuietOpenMesh() : log_(::omlog().is_enabled()), err_(::omerr().is_enabled()), out_(::omout().is_enabled()) {
    ::omlog().disable();
    ::omerr().disable();
    ::omout().disable();
  }
  ~QuietOpenMesh() {
    if (log_) ::omlog().enable();
    if (err_) ::omerr().enable();
    if (out_) ::omout().enable();
  }
  QuietOpenMesh(const QuietOpenMesh&) = delete;
  QuietOpenMesh& operator=(const QuietOpenMesh&) = delete;

 private:
  bool log_, err_, out_;
};

}  // namespace avenues
