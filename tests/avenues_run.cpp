// Avenues tests — running programs by argument vector, and the fixture (tests/avenues_run.h).
#include "tests/avenues_run.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <thread>
#include <utility>

extern char** environ;

namespace fs = std::filesystem;

namespace avenues::testing {

namespace {

/// Everything in the memory file `fd` (from its start).
std::string read_all(int fd) {
  std::string out;
  if (fd < 0 || ::lseek(fd, 0, SEEK_SET) != 0) return out;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n > 0) out.append(buf, size_t(n));
    else if (n == 0 || errno != EINTR) break;
  }
  return out;
}

/// The test process's environment less `unset` and the names `set` gives, then `set`.
std::vector<std::string> child_environment(const RunOptions& options) {
  auto name_of = [](const std::string& entry) { return entry.substr(0, entry.find('=')); };
  std::vector<std::string> names = options.unset_env;
  for (const std::string& entry : options.set_env) names.push_back(name_of(entry));
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::find(names.begin(), names.end(), name_of(*e)) == names.end()) env.emplace_back(*e);
  env.insert(env.end(), options.set_env.begin(), options.set_env.end());
  return env;
}

/// The strings' characters, then a null pointer: argv or envp for posix_spawnp.
std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> out;
  for (std::string& s : strings) out.push_back(s.data());
  out.push_back(nullptr);
  return out;
}

}  // namespace

Child::Child(Child&& other) noexcept { *this = std::move(other); }

Child& Child::operator=(Child&& other) noexcept {
  if (this != &other) {
    release();
    pid_ = std::exchange(other.pid_, -1);
    out_fd_ = std::exchange(other.out_fd_, -1);
    err_fd_ = std::exchange(other.err_fd_, -1);
    reaped_ = std::exchange(other.reaped_, false);
    status_ = other.status_;
  }
  return *this;
}

Child::~Child() { release(); }

void Child::release() {
  if (pid_ > 0 && !reaped_) {
    // SIGTERM first, which timeout(1) and mpirun pass on to what they run; SIGKILL after 5 s.
    ::kill(pid_, SIGTERM);
    for (int i = 0; i < 500 && !reap(WNOHANG); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!reaped_) {
      ::kill(pid_, SIGKILL);
      reap(0);
    }
  }
  for (int* fd : {&out_fd_, &err_fd_})
    if (*fd >= 0) ::close(std::exchange(*fd, -1));
  pid_ = -1;
  reaped_ = false;
}

Child start_argv(const std::vector<std::string>& argv, const RunOptions& options) {
  Child child;
  if (argv.empty() || argv[0].empty()) {
    ADD_FAILURE() << "start_argv: no program named";
    return child;
  }
  std::vector<std::string> args = argv;
  if (options.timeout_s > 0) args.insert(args.begin(), {"timeout", std::to_string(options.timeout_s)});
  child.out_fd_ = ::memfd_create("stdout", MFD_CLOEXEC);
  child.err_fd_ = ::memfd_create("stderr", MFD_CLOEXEC);
  if (child.out_fd_ < 0 || child.err_fd_ < 0) {
    ADD_FAILURE() << "cannot run " << args[0] << ": memfd_create: " << std::strerror(errno);
    return child;
  }
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  if (!options.cwd.empty()) posix_spawn_file_actions_addchdir_np(&files, options.cwd.c_str());
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&files, child.out_fd_, 1);  // dup2 clears close-on-exec
  posix_spawn_file_actions_adddup2(&files, child.err_fd_, 2);
  std::vector<std::string> env = child_environment(options);
  std::vector<char*> arg_pointers = pointers(args), env_pointers = pointers(env);
  pid_t pid = -1;
  const int err = ::posix_spawnp(&pid, args[0].c_str(), &files, nullptr, arg_pointers.data(), env_pointers.data());
  posix_spawn_file_actions_destroy(&files);
  if (err != 0) {
    ADD_FAILURE() << "cannot run " << args[0] << (options.cwd.empty() ? "" : " in " + options.cwd.string()) << ": "
                  << std::strerror(err);
    return child;
  }
  child.pid_ = pid;
  return child;
}

bool Child::reap(int flags) {
  if (reaped_) return true;
  int s = 0;
  pid_t got = 0;
  while ((got = ::waitpid(pid_, &s, flags)) < 0 && errno == EINTR) {
  }
  if (got == 0) return false;
  reaped_ = true;
  if (got != pid_) ADD_FAILURE() << "cannot wait for process " << pid_ << ": " << std::strerror(errno);
  status_ = got != pid_ ? -1 : WIFEXITED(s) ? WEXITSTATUS(s) : WIFSIGNALED(s) ? 128 + WTERMSIG(s) : -1;
  return true;
}

bool running(Child& child) { return child.pid_ > 0 && !child.reap(WNOHANG); }

Outcome finish(Child& child) {
  Outcome r;
  if (child.pid_ <= 0) return r;
  child.reap(0);
  r.status = child.status_;
  r.out = read_all(child.out_fd_);
  r.err = read_all(child.err_fd_);
  child.release();
  return r;
}

Outcome run_argv(const std::vector<std::string>& argv, const RunOptions& options) {
  Child child = start_argv(argv, options);
  return finish(child);
}

std::vector<std::string> avenues_argv(const std::vector<std::string>& args) {
  std::vector<std::string> argv{AVENUES_BINARY};
  argv.insert(argv.end(), args.begin(), args.end());
  return argv;
}

// --- the fixture ----------------------------------------------------------------------

namespace {

/// "avenues-SUITE", the start of the test's folder's name (TempDir adds the process and the test).
std::string folder_prefix() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return std::string("avenues-") + (info ? info->test_suite_name() : "test");
}

/// `options`, run in the test's folder when they name no other.
RunOptions in_folder(RunOptions options, const fs::path& dir) {
  if (options.cwd.empty()) options.cwd = dir;
  return options;
}

}  // namespace

AvenuesRun::AvenuesRun() : dir_(folder_prefix()) {}

AvenuesRun::~AvenuesRun() {
  if (HasFailure()) dir_.keep();
}

std::set<std::string> AvenuesRun::files() const {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir())) out.insert(fs::relative(e.path(), dir()).string());
  return out;
}

Outcome AvenuesRun::run(const std::vector<std::string>& args, const RunOptions& options) {
  return avenues::testing::run_argv(avenues_argv(args), in_folder(options, dir()));
}

Child AvenuesRun::start(const std::vector<std::string>& args, const RunOptions& options) {
  return avenues::testing::start_argv(avenues_argv(args), in_folder(options, dir()));
}

Outcome AvenuesRun::run_argv(const std::vector<std::string>& argv, const RunOptions& options) {
  return avenues::testing::run_argv(argv, in_folder(options, dir()));
}

Child AvenuesRun::start_argv(const std::vector<std::string>& argv, const RunOptions& options) {
  return avenues::testing::start_argv(argv, in_folder(options, dir()));
}

}  // namespace avenues::testing
