// The tasks of a sweep, run by a scheduler or by texsim itself (docs/cluster.md).
//
// A sweep (texsim explore) is cut into tasks, each one command line that measures some points and
// puts their results in the results store (reports/result_store.h). texsim runs the tasks itself
// (--jobs N: a pool of child processes), or writes them for a scheduler to run (--emit slurm DIR,
// --emit parallel DIR), in a directory:
//   README.txt     how to run the tasks and collect their results
//   commands.txt   task k's command line on line k + 1 (k from 0)
//   task.sh        `task.sh K` runs task K: its output in logs/task-K.log, its exit code in
//                  status/task-K (written when it ends, by rename)
//   sweep.sbatch   Slurm: a job array of the tasks (`sbatch DIR/sweep.sbatch`)
//   tasks.txt, run-parallel.sh
//                  GNU parallel: one `task.sh K` per line, and the parallel command line with a
//                  job log, so that running it again re-runs the failed tasks (--resume-failed)
// The sweep's own manifest (which points, their keys and tasks) is the caller's.
#pragma once
#include <map>
#include <string>
#include <vector>

namespace tex {

enum class Scheduler { Slurm, Parallel };
// "slurm" | "parallel"; throws tex::Error naming the accepted values.
Scheduler parse_scheduler(const std::string& name);
const char* scheduler_name(Scheduler s);

struct EmitOptions {
  Scheduler scheduler = Scheduler::Slurm;
  std::string dir;            // the sweep's directory (made absolute)
  int throttle = 0;           // Slurm: at most this many tasks at once (--array=0-K%T); 0: no limit
  std::string sshloginfile;   // GNU parallel: the hosts (--sshloginfile), "" = this machine
  std::string job_name = "texsim";
  std::string collect;        // the command that collects the results (README.txt names it)
  std::string manifest_name;  // the caller's manifest (sweep.txt, render.txt), written with the task files
  std::string manifest;
};
// Throws tex::Error for a throttle below 0 or an --sshloginfile that is not a file (before the work).
void check_emit_options(const EmitOptions& opts);
// How to start the emitted tasks, for a summary line: "submit: sbatch DIR/sweep.sbatch" or "run:
// DIR/run-parallel.sh".
std::string emit_hint(const EmitOptions& opts);

// Makes ready a directory to emit into: a new or empty one, or one an earlier --emit wrote (its
// manifest, sweep.txt or render.txt, says so), whose task files, status files, logs and job log
// are removed (they would speak for the new tasks). Throws tex::Error for any other directory
// (nothing of the user's is removed) or a path that is not a directory.
void prepare_emit_dir(const std::string& dir);

// Writes the task files (above) for `commands` (each an argv) and the caller's manifest into
// opts.dir (created if need be), all or nothing; no tasks: the manifest and README.txt alone.
// Throws tex::Error.
void emit_tasks(const EmitOptions& opts, const std::vector<std::vector<std::string>>& commands);
// The same for tasks given as shell lines (several commands joined with &&, a cd first).
void emit_task_lines(const EmitOptions& opts, const std::vector<std::string>& lines);

// What became of task k of an emitted sweep: its status file (task.sh), or GNU parallel's job log
// (a task.sh killed before it could write its status), or nothing yet.
struct TaskReport {
  bool ended = false;   // an exit code is known
  int exit_code = 0;    // (128 + N: killed by signal N)
  std::string log_tail; // the last lines of logs/task-K.log ("" if none)
};
TaskReport task_report(const std::string& dir, size_t k);

// The end of a --collect that found items (points, frames) missing: names each task of `missing`
// (task -> its items missing) on standard error with its fate (exit code or signal, or not run)
// and its log's last lines, writes DIR/resubmit.sh for exactly those tasks, and throws the
// tex::Error that says so. `what`: "points" or "frames"; `collect`: the command that collects.
[[noreturn]] void fail_collect(const std::string& dir, Scheduler scheduler, const std::map<size_t, size_t>& missing,
                               size_t items, size_t tasks, const std::string& what, const std::string& collect);

// Writes DIR/resubmit.sh, which runs exactly these tasks again (Slurm: `sbatch --array=LIST`;
// GNU parallel: run-parallel.sh, whose --resume-failed re-runs the failed ones and runs the rest).
// Returns its path.
std::string write_resubmit(const std::string& dir, Scheduler scheduler, const std::vector<size_t>& tasks);

// Runs the commands here, `parallel` at a time (child processes; each one's standard output to
// /dev/null and standard error to a temporary file). On the first failure stops the others and
// throws tex::Error with its last line of error and its command. `progress`: "\rexplore: i/n
// tasks" on standard error.
void run_tasks_here(const std::vector<std::vector<std::string>>& commands, int parallel, bool progress);

// Runs argv with this process's standard output and error and waits for it: its exit code, or
// 128 + the signal that ended it. Throws tex::Error if it cannot start.
int run_command(const std::vector<std::string>& argv);

// A word for a POSIX shell: as it is if safe, else in single quotes.
std::string shell_quote(const std::string& word);
std::string shell_line(const std::vector<std::string>& argv);

}  // namespace tex
