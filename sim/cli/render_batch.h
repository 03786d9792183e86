// texsim render's frame batches on a scheduler (docs/cluster.md, "Frame batches"):
// `render ... --frames N --emit slurm|parallel DIR` writes one task per --frames-per-task frames,
// each frame a `texsim render ... --frame F` of its own with its picture and statistics in
// DIR/frames/; `render --collect DIR` checks every frame is there and merges the statistics into
// DIR/frames.json in frame order, or names the tasks that failed or did not run and writes a
// resubmit script for exactly those.
#pragma once
#include <string>
#include <vector>

namespace tex {

struct RenderBatchArgs {
  std::string scheduler, dir;        // --emit SCHEDULER DIR
  int frames = 1, frames_per_task = 1;
  int throttle = 0;                  // Slurm: tasks at once
  std::string sshloginfile;          // GNU parallel: hosts
  std::string out;                   // the render's --out: its stem and extension name the frames
  std::string self;                  // this executable
  std::vector<std::string> args;     // the render's arguments, without --emit, --out, --stats, --frame and the batch's own
};

int emit_render_batch(const RenderBatchArgs& a);
int collect_render_batch(const std::string& dir);

// The arguments of `texsim render` (argv after "render") without the options that a batch sets
// per frame or that are its own: each given as `--name value`, `--name=value` (and -o VALUE).
std::vector<std::string> render_task_arguments(const std::vector<std::string>& render_args);

}  // namespace tex
