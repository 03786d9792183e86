// The output files of one command: checked before the work, written all or nothing, and never
// harming what is at a path.
//
// declare() checks an output before any work starts and decides how it is written:
//  - a new path, or an existing regular file (through any symlinks: the link stays and its target
//    is written): the data goes to NAME.partial-XXXXXX.EXT next to the target and commit() renames
//    it into place once every output of the command is complete;
//  - "-" (standard output), /dev/stdout, a character device or a FIFO: written directly,
//    streaming (what was written cannot be taken back);
//  - refused with a one-line tex::Error: a directory, a block device, a socket, a directory that
//    does not exist or cannot be written, a read-only file, a path that is one of the command's
//    inputs (same device and inode, whatever the name) or another of its outputs.
// Without commit(), the destructor removes every staged file; SIGINT, SIGTERM, SIGHUP and SIGPIPE
// (`-o - | head`) remove them too before the process ends as the signal would end it. No existing
// file is touched until commit().
#pragma once
#include <sys/types.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace tex {

class OutputFile {
 public:
  const std::string& path() const { return path_; }  // as the user gave it
  // Where to write now: the staged file, or the stream itself (for writers that open by name).
  const std::string& write_path() const { return write_path_; }
  bool direct() const { return direct_; }
  // Opens write_path() for writing ("-" is standard output). Throws tex::Error.
  std::FILE* open();
  // Flushes and closes what open() returned; throws tex::Error naming the path on a write error.
  void close();

 private:
  friend class OutputSet;
  std::string option_, path_, write_path_, target_;  // target_: where commit() renames to
  bool direct_ = false;
  mode_t mode_ = 0;  // of the committed file
  std::FILE* file_ = nullptr;
};

class OutputSet {
 public:
  // Kinds of output: Stream takes any target that can be written in order; File needs a regular
  // file (writers that seek: images, waveforms).
  enum class Kind { Stream, File };

  OutputSet();
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // An input of the command (a path that does not exist, e.g. a built-in pattern, is ignored).
  void add_input(const std::string& path, const std::string& option);
  // Declares and checks an output; `option` names it in errors, e.g. "--out". Outputs must be
  // declared after the inputs. The reference stays valid for the set's lifetime.
  OutputFile& declare(const std::string& path, const std::string& option, Kind kind = Kind::Stream);
  // Creates the directory DIR (and parents) for outputs inside it; a directory created here is
  // removed again if the command fails and leaves it empty. Throws tex::Error.
  void make_directory(const std::string& dir, const std::string& option);
  // Renames every staged output into place, in declaration order. Throws tex::Error.
  void commit();
  // Renames one staged output into place now (a waveform of a failed simulation); false if it
  // is empty or was not staged.
  bool keep(OutputFile& output);

 private:
  struct Input {
    std::string path, option;
    dev_t dev;
    ino_t ino;
  };
  bool place(OutputFile& output);  // chmod + rename a staged output onto its target
  std::vector<Input> inputs_;
  std::vector<std::unique_ptr<OutputFile>> outputs_;
  std::vector<std::string> created_dirs_;
  bool committed_ = false;
};

// Ends the process at once with `status` (no destructors run), first removing every live set's
// staged files and created directories: for a thread that must stop a run another thread cannot
// leave (a model import past its time, workloads/mesh_scene.cpp).
[[noreturn]] void exit_removing_outputs(int status);

}  // namespace tex
