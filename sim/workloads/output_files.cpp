#include "workloads/output_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "model/error.h"

namespace tex {

namespace fs = std::filesystem;

namespace {

// Staged files and created directories of every live OutputSet, for the signal handler. Changed
// only while the signals are blocked, so the handler never sees a vector being reallocated.
std::vector<std::string>* g_staged = nullptr;
std::vector<std::string>* g_created_dirs = nullptr;
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

void remove_staged() {
  if (!g_staged) return;
  for (const std::string& p : *g_staged) ::unlink(p.c_str());
  for (auto it = g_created_dirs->rbegin(); it != g_created_dirs->rend(); ++it) ::rmdir(it->c_str());
}

void on_fatal_signal(int sig) {
  remove_staged();
  ::signal(sig, SIG_DFL);
  ::raise(sig);  // delivered when the handler returns: the process ends as the signal would end it
}

void install_handlers_once() {
  if (g_staged) return;
  g_staged = new std::vector<std::string>;  // lives as long as the process: the handler may run at exit
  g_created_dirs = new std::vector<std::string>;
  for (int sig : kCleanupSignals) {
    struct sigaction sa {}, old {};
    sa.sa_handler = on_fatal_signal;
    sigemptyset(&sa.sa_mask);
    for (int s : kCleanupSignals) sigaddset(&sa.sa_mask, s);
    sigaction(sig, &sa, &old);
    if (old.sa_handler == SIG_IGN) sigaction(sig, &old, nullptr);  // e.g. SIGHUP under nohup
  }
}

class BlockSignals {
 public:
  BlockSignals() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : kCleanupSignals) sigaddset(&set, s);
    pthread_sigmask(SIG_BLOCK, &set, &old_);
  }
  ~BlockSignals() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }

 private:
  sigset_t old_;
};

void unregister(std::vector<std::string>& list, const std::string& path) {
  BlockSignals block;
  for (auto it = list.begin(); it != list.end(); ++it)
    if (*it == path) {
      list.erase(it);
      return;
    }
}

std::string errno_text() { return std::strerror(errno); }

// Where a chain of symbolic links ends (the path itself if it is not a link); the end need not exist.
fs::path follow_links(fs::path p) {
  for (int hops = 0; hops < 40; ++hops) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(p, ec))) return p;
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) return p;
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  throw Error(p.string() + ": too many levels of symbolic links");
}

std::string kind_of(mode_t m) {
  if (S_ISBLK(m)) return "a block device";
  if (S_ISSOCK(m)) return "a socket";
  return "not a regular file";
}

}  // namespace

// ---------------------------------------------------------------- OutputFile

std::FILE* OutputFile::open() {
  if (write_path_ == "-") {
    file_ = stdout;
  } else {
    file_ = std::fopen(write_path_.c_str(), "wb");
    if (!file_) throw Error(path_ + ": cannot write (" + errno_text() + ")");
  }
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  return file_;
}

void OutputFile::close() {
  if (!file_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  errno = 0;
  bool ok = std::fflush(f) == 0 && !std::ferror(f);
  const std::string why = errno ? errno_text() : "write error";
  if (f != stdout) ok = std::fclose(f) == 0 && ok;
  if (!ok) throw Error(path_ + ": cannot write (" + why + ")");
}

// ---------------------------------------------------------------- OutputSet

OutputSet::OutputSet() { install_handlers_once(); }

OutputSet::~OutputSet() {
  for (auto& o : outputs_)
    if (o->file_ && o->file_ != stdout) std::fclose(o->file_);
  if (committed_) return;
  for (auto& o : outputs_)
    if (!o->direct_ && !o->write_path_.empty()) {
      ::unlink(o->write_path_.c_str());
      unregister(*g_staged, o->write_path_);
    }
  for (auto it = created_dirs_.rbegin(); it != created_dirs_.rend(); ++it) {
    ::rmdir(it->c_str());  // only if empty: never removes what was there before
    unregister(*g_created_dirs, *it);
  }
}

void OutputSet::add_input(const std::string& path, const std::string& option) {
  struct stat st {};
  if (path == "-" ? ::fstat(STDIN_FILENO, &st) != 0 : ::stat(path.c_str(), &st) != 0) return;
  inputs_.push_back({path, option, st.st_dev, st.st_ino});
}

void OutputSet::make_directory(const std::string& dir, const std::string& option) {
  if (dir.empty()) throw Error(option + ": empty directory name");
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = fs::absolute(dir).lexically_normal(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing.push_back(p);
    if (p == p.parent_path()) break;
  }
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw Error(dir + ": exists and is not a directory (" + option + ")");
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (::mkdir(it->c_str(), 0777) != 0)
      throw Error(dir + ": cannot create directory " + it->string() + " (" + errno_text() + ")");
    BlockSignals block;
    created_dirs_.push_back(it->string());
    g_created_dirs->push_back(it->string());
  }
}

OutputFile& OutputSet::declare(const std::string& path, const std::string& option, Kind kind) {
  auto out = std::make_unique<OutputFile>();
  out->option_ = option;
  out->path_ = path;
  auto refuse = [&](const std::string& why) -> Error { return Error(path + ": " + why + " (" + option + ")"); };
  if (path.empty()) throw Error(option + ": empty file name");

  struct stat st {};
  const bool is_stdout = path == "-";
  const int found = is_stdout ? ::fstat(STDOUT_FILENO, &st) : ::stat(path.c_str(), &st);
  if (found == 0) {
    for (const Input& in : inputs_)
      if (in.dev == st.st_dev && in.ino == st.st_ino)
        throw refuse("is also the input " + in.option + " " + in.path + "; refusing to overwrite an input");
    for (const auto& other : outputs_) {
      struct stat os {};
      const std::string& p = other->direct_ ? other->write_path_ : other->target_;
      if ((p == "-" ? ::fstat(STDOUT_FILENO, &os) : ::stat(p.c_str(), &os)) == 0 && os.st_dev == st.st_dev &&
          os.st_ino == st.st_ino && !S_ISCHR(st.st_mode))
        throw refuse("is also the output " + other->option_ + "; give each output its own file");
    }
  }
  if (is_stdout) {
    if (kind == Kind::File) throw refuse("this output cannot go to standard output; give a file name");
    out->direct_ = true;
    out->write_path_ = "-";
  } else if (found == 0 && !S_ISREG(st.st_mode)) {
    if (S_ISDIR(st.st_mode)) throw refuse("is a directory");
    if (!S_ISCHR(st.st_mode) && !S_ISFIFO(st.st_mode)) throw refuse("is " + kind_of(st.st_mode) + "; refusing to write to it");
    if (kind == Kind::File) throw refuse("is not a regular file, and this output needs one (it is written with seeks)");
    out->direct_ = true;  // a device or a pipe: written in place, never replaced
    out->write_path_ = path;
  } else {
    if (found != 0 && errno != ENOENT) throw refuse(errno_text());
    if (found == 0 && ::access(path.c_str(), W_OK) != 0) throw refuse("is not writable (" + errno_text() + ")");
    // A symlink stays: its final target is what gets written (or created).
    const fs::path target = follow_links(path);
    const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw refuse("directory " + dir.string() + " does not exist");
    if (::access(dir.c_str(), W_OK | X_OK) != 0) throw refuse("directory " + dir.string() + " is not writable");
    for (const auto& other : outputs_)
      if (!other->direct_ && fs::absolute(other->target_).lexically_normal() == fs::absolute(target).lexically_normal())
        throw refuse("is also the output " + other->option_ + "; give each output its own file");
    if (found == 0) {
      out->mode_ = st.st_mode & 07777;
    } else {
      const mode_t mask = ::umask(0);
      ::umask(mask);
      out->mode_ = 0666 & ~mask;
    }
    out->target_ = target.string();
    // Staged next to the target (same file system: the rename is atomic), keeping the extension
    // so that image writers still pick the format from it.
    const std::string ext = target.extension().string();
    std::string tmpl = (dir / (target.stem().string() + ".partial-XXXXXX" + ext)).string();
    BlockSignals block;  // registered before a signal could strand it
    const int fd = ::mkstemps(tmpl.data(), int(ext.size()));
    if (fd < 0) throw refuse("cannot create a file in " + dir.string() + " (" + errno_text() + ")");
    ::close(fd);
    out->write_path_ = tmpl;
    g_staged->push_back(tmpl);
  }
  outputs_.push_back(std::move(out));
  return *outputs_.back();
}

bool OutputSet::place(OutputFile& o) {
  ::chmod(o.write_path_.c_str(), o.mode_);
  if (::rename(o.write_path_.c_str(), o.target_.c_str()) != 0) return false;
  unregister(*g_staged, o.write_path_);
  o.write_path_.clear();
  return true;
}

bool OutputSet::keep(OutputFile& o) {
  if (o.direct_ || o.write_path_.empty()) return false;
  struct stat st {};
  if (::stat(o.write_path_.c_str(), &st) != 0 || st.st_size == 0) return false;
  return place(o);
}

void OutputSet::commit() {
  for (auto& o : outputs_) o->close();
  for (auto& o : outputs_)
    if (!o->direct_ && !o->write_path_.empty() && !place(*o))
      throw Error(o->path_ + ": cannot move the result into place (" + errno_text() + ")");
  committed_ = true;
  BlockSignals block;
  for (const std::string& d : created_dirs_) unregister(*g_created_dirs, d);
}

void exit_removing_outputs(int status) {
  BlockSignals block;
  remove_staged();
  std::_Exit(status);
}

}  // namespace tex
