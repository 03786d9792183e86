#include "reports/sweep_tasks.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "model/error.h"
#include "workloads/output_files.h"

extern char** environ;

namespace tex {

namespace fs = std::filesystem;

namespace {

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The last `n` non-empty lines of a text, joined by " | ".
std::string last_lines(const std::string& text, int n) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") != std::string::npos) lines.push_back(line);
  }
  std::string out;
  for (size_t i = lines.size() > size_t(n) ? lines.size() - size_t(n) : 0; i < lines.size(); ++i)
    out += (out.empty() ? "" : " | ") + lines[i];
  return out;
}

void write_text(OutputSet& outputs, const fs::path& path, const std::string& text) {
  OutputFile& f = outputs.declare(path.string(), "--emit");
  std::fputs(text.c_str(), f.open());
  f.close();
}

// Starts argv (posix_spawn: safe beside threads); with an err_path, stdout to /dev/null and stderr
// to that file, else both this process's. Returns the pid.
pid_t spawn(const std::vector<std::string>& argv, const std::string& err_path) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (!err_path.empty()) {
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw Error("cannot start " + argv[0] + ": " + std::strerror(rc));
  return pid;
}

// Removes a directory tree when it goes out of scope.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "texsim-tasks-XXXXXX").string();
    if (!mkdtemp(t.data())) throw Error("cannot create a temporary directory in " + fs::temp_directory_path().string());
    path = t;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

}  // namespace

void prepare_emit_dir(const std::string& dir_name) {
  const fs::path dir = fs::absolute(dir_name);
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec)) throw Error("--emit " + dir_name + ": not a directory");
  if (fs::is_empty(dir, ec)) return;
  bool ours = false;
  for (const char* manifest : {"sweep.txt", "render.txt"}) {
    std::ifstream in(dir / manifest);
    std::string first;
    ours = ours || (std::getline(in, first) && first.rfind("texsim ", 0) == 0);
  }
  if (!ours)
    throw Error("--emit " + dir_name + ": the directory holds other files (no sweep.txt or render.txt of an earlier "
                "--emit); give a new directory");
  // The earlier emission's traces would speak for the new tasks: its status files and logs, and
  // GNU parallel's job log (--resume-failed would skip the tasks it says succeeded).
  for (const char* sub : {"status", "logs"})
    for (const auto& e : fs::directory_iterator(dir / sub, ec))
      if (e.is_regular_file(ec)) fs::remove(e.path(), ec);
  for (const char* f : {"parallel.joblog", "resubmit.sh", "tasks.txt", "run-parallel.sh", "sweep.sbatch", "commands.txt", "README.txt",
                        "task.sh", "sweep.txt", "render.txt", "explore.csv", "frames.json"})
    fs::remove(dir / f, ec);
}

Scheduler parse_scheduler(const std::string& name) {
  if (name == "slurm") return Scheduler::Slurm;
  if (name == "parallel") return Scheduler::Parallel;
  throw Error("--emit " + name + ": the schedulers are slurm (a Slurm job array) and parallel (GNU parallel)");
}

const char* scheduler_name(Scheduler s) { return s == Scheduler::Slurm ? "slurm" : "parallel"; }

std::string shell_quote(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./:=,+@%") ==
                           std::string::npos)
    return word;
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string shell_line(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& w : argv) line += (line.empty() ? "" : " ") + shell_quote(w);
  return line;
}

void check_emit_options(const EmitOptions& o) {
  if (o.throttle < 0) throw Error("--throttle " + std::to_string(o.throttle) + " is negative");
  std::error_code ec;
  if (!o.sshloginfile.empty() && !fs::is_regular_file(o.sshloginfile, ec))
    throw Error("--sshloginfile " + o.sshloginfile + ": no such file");
}

std::string emit_hint(const EmitOptions& o) {
  const fs::path dir = fs::absolute(o.dir);
  return o.scheduler == Scheduler::Slurm ? "submit: sbatch " + (dir / "sweep.sbatch").string()
                                         : "run: " + (dir / "run-parallel.sh").string();
}

void emit_tasks(const EmitOptions& o, const std::vector<std::vector<std::string>>& commands) {
  std::vector<std::string> lines;
  for (const auto& c : commands) lines.push_back(shell_line(c));
  emit_task_lines(o, lines);
}

void emit_task_lines(const EmitOptions& o, const std::vector<std::string>& commands) {
  const fs::path dir = fs::absolute(o.dir);
  OutputSet outputs;
  outputs.make_directory(dir.string(), "--emit");
  if (!o.manifest_name.empty()) write_text(outputs, dir / o.manifest_name, o.manifest);
  const size_t n = commands.size();
  const std::string run = o.scheduler == Scheduler::Slurm
                              ? "sbatch " + shell_quote((dir / "sweep.sbatch").string()) +
                                    "   (add the #SBATCH lines your site needs to sweep.sbatch first)"
                              : shell_quote((dir / "run-parallel.sh").string()) + " [--jobs N]   (options go to GNU parallel)";
  write_text(outputs, dir / "README.txt",
             std::to_string(n) + " tasks of " + o.job_name + ", written by texsim --emit " + scheduler_name(o.scheduler) +
                 " (docs/cluster.md).\n" +
                 (n ? "Run them:  " + run + "\n" : std::string("Nothing to run: every result is in the store.\n")) +
                 "Then:      " + o.collect + "\n"
                 "A task that failed or did not run is named by the collect, with its exit code and the last lines of\n"
                 "logs/task-K.log, and resubmit.sh (written then) runs exactly those tasks again.\n");
  if (n == 0) {
    outputs.commit();
    return;
  }
  outputs.make_directory((dir / "logs").string(), "--emit");
  outputs.make_directory((dir / "status").string(), "--emit");
  std::string lines;
  for (const std::string& c : commands) {
    if (c.find('\n') != std::string::npos) throw Error("--emit: a task's command line holds a line break");
    lines += c + "\n";
  }
  write_text(outputs, dir / "commands.txt", lines);
  write_text(outputs, dir / "task.sh",
             "#!/bin/bash\n"
             "# task.sh K: runs task K of this sweep (line K + 1 of commands.txt), its output in logs/task-K.log\n"
             "# and its exit code in status/task-K (written when it ends). Written by texsim --emit.\n"
             "set -u\n"
             "k=$1\n"
             "dir=$(cd \"$(dirname \"$0\")\" && pwd)\n"
             "cmd=$(sed -n \"$((k + 1))p\" \"$dir/commands.txt\")\n"
             "[ -n \"$cmd\" ] || { echo \"task.sh: no task $k in $dir/commands.txt\" >&2; exit 2; }\n"
             "rm -f \"$dir/status/task-$k\"\n"
             "bash -c \"$cmd\" > \"$dir/logs/task-$k.log\" 2>&1\n"
             "code=$?\n"
             "echo \"$code\" > \"$dir/status/.task-$k.$$\" && mv -f \"$dir/status/.task-$k.$$\" \"$dir/status/task-$k\"\n"
             "exit \"$code\"\n");
  if (o.scheduler == Scheduler::Slurm) {
    write_text(outputs, dir / "sweep.sbatch",
               "#!/bin/bash\n"
               "#SBATCH --job-name=" + o.job_name + "\n"
               "#SBATCH --array=0-" + std::to_string(n - 1) + (o.throttle > 0 ? "%" + std::to_string(o.throttle) : "") + "\n"
               "#SBATCH --output=" + (dir / "logs" / "slurm-%A_%a.out").string() + "\n"
               "# One array task per line of commands.txt. Add the #SBATCH lines your site needs\n"
               "# (--partition, --time, --mem, --account). Submit: sbatch " + (dir / "sweep.sbatch").string() + "\n"
               "exec " + shell_quote((dir / "task.sh").string()) + " \"$SLURM_ARRAY_TASK_ID\"\n");
  } else {
    std::string tasks;
    for (size_t k = 0; k < n; ++k) tasks += shell_quote((dir / "task.sh").string()) + " " + std::to_string(k) + "\n";
    write_text(outputs, dir / "tasks.txt", tasks);
    write_text(outputs, dir / "run-parallel.sh",
               "#!/bin/bash\n"
               "# Runs this sweep's tasks with GNU parallel (options given here go to parallel, e.g. --jobs 8).\n"
               "# Run it again after a failure: --resume-failed re-runs the failed tasks and runs those not yet run.\n"
               "exec parallel --joblog " + shell_quote((dir / "parallel.joblog").string()) + " --resume-failed" +
                   (o.sshloginfile.empty() ? "" : " --sshloginfile " + shell_quote(fs::absolute(o.sshloginfile).string())) +
                   " \"$@\" < " + shell_quote((dir / "tasks.txt").string()) + "\n");
  }
  outputs.commit();
  for (const char* script : {"task.sh", "sweep.sbatch", "run-parallel.sh"}) {
    std::error_code ec;
    if (fs::exists(dir / script, ec))
      fs::permissions(dir / script, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                      fs::perm_options::add, ec);
  }
}

TaskReport task_report(const std::string& dir_name, size_t k) {
  const fs::path dir(dir_name);
  TaskReport r;
  const std::string log = read_all(dir / "logs" / ("task-" + std::to_string(k) + ".log"));
  r.log_tail = last_lines(log, 3);
  std::ifstream status(dir / "status" / ("task-" + std::to_string(k)));
  if (status >> r.exit_code) {
    r.ended = true;
    return r;
  }
  // GNU parallel's job log: Seq Host Starttime JobRuntime Send Receive Exitval Signal Command, tab
  // separated; a re-run adds a line of the same Seq (the last one counts).
  std::ifstream joblog(dir / "parallel.joblog");
  std::string line;
  while (std::getline(joblog, line)) {
    std::vector<std::string> f;
    std::istringstream fields(line);
    std::string item;
    while (std::getline(fields, item, '\t')) f.push_back(item);
    if (f.size() < 9 || f[0] != std::to_string(k + 1)) continue;
    r.ended = true;
    const int signal = std::atoi(f[7].c_str());
    r.exit_code = signal ? 128 + signal : std::atoi(f[6].c_str());
  }
  return r;
}

void fail_collect(const std::string& dir, Scheduler scheduler, const std::map<size_t, size_t>& missing, size_t items,
                  size_t tasks, const std::string& what, const std::string& collect) {
  size_t count = 0;
  std::vector<size_t> failed;
  for (const auto& [t, n] : missing) {
    count += n;
    failed.push_back(t);
    const TaskReport r = task_report(dir, t);
    const std::string fate = !r.ended            ? std::string("has not run, or has not ended")
                             : r.exit_code == 0  ? "ended with exit code 0 but its " + what + " are not there (a store or directory the task did not share?)"
                             : r.exit_code > 128 ? "killed by signal " + std::to_string(r.exit_code - 128)
                                                 : "failed, exit code " + std::to_string(r.exit_code);
    std::fprintf(stderr, "texsim: task %zu (%zu %s missing): %s%s%s\n", t, n, what.c_str(), fate.c_str(),
                 r.log_tail.empty() ? "" : ": ", r.log_tail.c_str());
  }
  const std::string resubmit = write_resubmit(dir, scheduler, failed);
  throw Error("--collect: " + std::to_string(count) + " of " + std::to_string(items) + " " + what + " are missing, in " +
              std::to_string(failed.size()) + " of " + std::to_string(tasks) + " tasks (above); " + resubmit +
              " runs them again, then " + collect);
}

std::string write_resubmit(const std::string& dir_name, Scheduler scheduler, const std::vector<size_t>& tasks) {
  const fs::path dir = fs::absolute(dir_name);
  std::string list;
  for (size_t k : tasks) list += (list.empty() ? "" : ",") + std::to_string(k);
  std::string text = "#!/bin/bash\n# Runs tasks " + list + " of this sweep again (texsim explore --collect found their points missing).\n";
  if (scheduler == Scheduler::Slurm)
    text += "exec sbatch --array=" + list + " \"$@\" " + shell_quote((dir / "sweep.sbatch").string()) + "\n";
  else
    text += "exec " + shell_quote((dir / "run-parallel.sh").string()) + " \"$@\"\n";
  OutputSet outputs;
  const fs::path path = dir / "resubmit.sh";
  write_text(outputs, path, text);
  outputs.commit();
  std::error_code ec;
  fs::permissions(path, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add, ec);
  return path.string();
}

int run_command(const std::vector<std::string>& argv) {
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = spawn(argv, "");
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) throw Error("waiting for " + argv[0] + ": " + std::strerror(errno));
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status);
}

void run_tasks_here(const std::vector<std::vector<std::string>>& commands, int parallel, bool progress) {
  TempDir tmp;
  std::map<pid_t, size_t> running;
  size_t next = 0, done = 0;
  auto err_path = [&](size_t k) { return (tmp.path / ("task" + std::to_string(k) + ".err")).string(); };
  auto stop_all = [&] {
    for (const auto& [pid, k] : running) kill(pid, SIGTERM);
    for (const auto& [pid, k] : running) waitpid(pid, nullptr, 0);
    running.clear();
  };
  try {
    while (done < commands.size()) {
      while (next < commands.size() && running.size() < size_t(parallel)) {
        running[spawn(commands[next], err_path(next))] = next;
        ++next;
      }
      int status = 0;
      const pid_t pid = waitpid(-1, &status, 0);
      if (pid < 0) throw Error(std::string("waiting for the tasks: ") + std::strerror(errno));
      const auto it = running.find(pid);
      if (it == running.end()) continue;
      const size_t k = it->second;
      running.erase(it);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        const std::string why = WIFSIGNALED(status) ? std::string("killed by signal ") + std::to_string(WTERMSIG(status))
                                                    : last_lines(read_all(err_path(k)), 1);
        throw Error("task " + std::to_string(k) + " failed: " + (why.empty() ? "(no message)" : why) +
                    " (command: " + shell_line(commands[k]) + ")");
      }
      ++done;
      if (progress) std::fprintf(stderr, "\rtexsim: %zu/%zu tasks", done, commands.size());
    }
  } catch (...) {
    stop_all();
    if (progress) std::fprintf(stderr, "\n");
    throw;
  }
  if (progress) std::fprintf(stderr, "\r%40s\r", "");
}

}  // namespace tex
