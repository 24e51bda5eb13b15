// Avenues — writing an output file all at once or not at all (core/atomic_file.h).
#include "core/atomic_file.h"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>

#include <fcntl.h>
#include <pthread.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

namespace avenues {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what, int err) {
  throw std::runtime_error("cannot write " + path + ": " + what +
                           (err ? std::string(": ") + std::strerror(err) : std::string()));
}

/// What a non-regular file is, for the message.
const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// --- the registry of pending temporary files, read by the signal handler --------------
//
// Fixed size, no allocation: a slot is claimed by compare-and-swap (free -> filling), its
// path copied in, then published (filling -> pending). The handler unlinks the pending
// ones; unlink() is async-signal-safe. A process with more temporary files pending at once
// than there are slots writes the rest unregistered.
constexpr int kSlots = 64;
constexpr size_t kPathMax = 4096;
enum SlotState : int { kFree = 0, kFilling = 1, kPending = 2 };
std::atomic<int> g_state[kSlots];
char g_path[kSlots][kPathMax];
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[3];

void remove_pending_and_reraise(int sig) {
  const int saved_errno = errno;
  for (int i = 0; i < kSlots; ++i)
    if (g_state[i].load(std::memory_order_acquire) == kPending) ::unlink(g_path[i]);
  // Die of the signal as without this handler (or hand it to the handler there was).
  for (int k = 0; k < 3; ++k)
    if (kSignals[k] == sig) ::sigaction(sig, &g_previous[k], nullptr);
  errno = saved_errno;
  ::raise(sig);
}

void install_handlers_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (int k = 0; k < 3; ++k) {
      struct sigaction old {};
      ::sigaction(kSignals[k], nullptr, &old);
      g_previous[k] = old;
      // A signal the process ignores (nohup) stays ignored; a handler someone installed
      // is kept and called after the files are removed.
      if (!(old.sa_flags & SA_SIGINFO) && old.sa_handler == SIG_IGN) continue;
      struct sigaction sa {};
      sa.sa_handler = remove_pending_and_reraise;
      sigemptyset(&sa.sa_mask);
      for (int s : kSignals) sigaddset(&sa.sa_mask, s);
      sa.sa_flags = SA_RESTART;
      ::sigaction(kSignals[k], &sa, nullptr);
    }
  });
}

/// Blocks the handled signals while alive: a temporary file is created and registered (or
/// renamed and unregistered) in one step as far as a signal can tell.
class BlockSignals {
 public:
  BlockSignals() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : kSignals) sigaddset(&set, s);
    ::pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~BlockSignals() { ::pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  BlockSignals(const BlockSignals&) = delete;
  BlockSignals& operator=(const BlockSignals&) = delete;

 private:
  sigset_t old_;
};

int register_pending(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (g_state[i].compare_exchange_strong(expected, kFilling, std::memory_order_acq_rel)) {
      std::memcpy(g_path[i], path.c_str(), path.size() + 1);
      g_state[i].store(kPending, std::memory_order_release);
      return i;
    }
  }
  return -1;
}

void unregister_pending(int slot) {
  if (slot >= 0) g_state[slot].store(kFree, std::memory_order_release);
}

}  // namespace

void check_output_path(const std::string& path) {
  if (path.empty()) fail("''", "an empty file name", 0);
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    fail(path, std::string("it is ") + kind_of(st.st_mode) + ", and only a regular file is written over", 0);
}

PendingTempFile::PendingTempFile(const std::string& target) : target_(target) {
  namespace fs = std::filesystem;
  check_output_path(target);
  const fs::path t(target);
  fs::path dir = t.parent_path();
  if (dir.empty()) dir = ".";
  std::string name = ".";  // built by appending: GCC 12 misreports "." + std::string&& (-Wrestrict)
  name += t.filename().string();
  name += ".tmp-XXXXXX";
  path_ = (dir / name).string();
  install_handlers_once();
  const BlockSignals blocked;
  fd_ = ::mkstemp(path_.data());
  if (fd_ < 0) fail(target, "cannot create a temporary file in " + dir.string(), errno);
  slot_ = register_pending(path_);
}

PendingTempFile::~PendingTempFile() {
  if (committed_) return;
  const BlockSignals blocked;
  if (fd_ >= 0) ::close(fd_);
  ::unlink(path_.c_str());
  unregister_pending(slot_);
}

void PendingTempFile::commit() {
  // mkstemp creates 0600: keep the mode of the file being replaced, else rw-r--r--.
  struct stat old {};
  ::fchmod(fd_, ::stat(target_.c_str(), &old) == 0 ? (old.st_mode & 07777) : 0644);
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0) fail(target_, "close failed", errno);
  // Checked again just before: something not a regular file may have appeared meanwhile.
  check_output_path(target_);
  const BlockSignals blocked;
  if (::rename(path_.c_str(), target_.c_str()) != 0) fail(target_, "rename failed", errno);
  unregister_pending(slot_);
  committed_ = true;
}

namespace {

/// A temporary file beside `path` holding `bytes`, not yet renamed over it.
std::unique_ptr<PendingTempFile> pending_with(const std::string& path, std::string_view bytes) {
  std::error_code ec;
  if (!path.empty() && std::filesystem::is_directory(path, ec)) fail(path, "is a directory", 0);
  auto tmp = std::make_unique<PendingTempFile>(path);
  const char* p = bytes.data();
  size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(tmp->fd(), p, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(path, "write failed", errno);
    }
    p += n;
    left -= static_cast<size_t>(n);
  }
  return tmp;
}

}  // namespace

void write_file_atomically(const std::string& path, std::string_view bytes) { pending_with(path, bytes)->commit(); }

void check_named_once(const std::vector<std::string>& paths) {
  std::set<std::filesystem::path> targets;
  for (const std::string& path : paths) {
    if (path.empty()) continue;
    std::error_code ec;
    const std::filesystem::path whole = std::filesystem::weakly_canonical(std::filesystem::absolute(path), ec);
    if (!targets.insert(ec ? std::filesystem::path(path) : whole).second)
      fail(path, "it is named twice among the files to write", 0);
  }
}

void write_files_atomically(const std::vector<std::pair<std::string, std::string>>& files) {
  std::vector<std::string> paths;
  for (const auto& [path, bytes] : files) paths.push_back(path);
  check_named_once(paths);
  std::vector<std::unique_ptr<PendingTempFile>> pending;
  for (const auto& [path, bytes] : files) pending.push_back(pending_with(path, bytes));
  for (auto& tmp : pending) tmp->commit();
}

}  // namespace avenues
