// `texsim explore`: sweeps the cached memory hierarchy over workloads (docs/memory.md §6).
//
// A sweep is the cartesian product of its lists: workload (scene or query trace) x rasterization
// order x texture format x cache size x ways x block shape x block order x memory latency x
// bandwidth x FIFO depth.
// Every point gets one CSV row. Hit rate and bytes per sample come from the golden model's caches;
// samples per clock from the model's timing layer (model/timing.h) at every point, compiled or not
// (--timing model, the default), or from the Verilated RTL wherever a compiled configuration holds
// the point (--timing rtl; the model times the rest). --confirm rtl re-runs every point a compiled
// configuration holds through the RTL and fails on any difference in cycles, memory waits, FIFO
// occupancy or cache counters. Through the RTL the model's caches run alongside and every line the
// RTL reads is checked against them.
//
// Outputs in OUT: explore.csv, then scripts/explore_plots.py's latency.png, hit_rate.png,
// bytes.png and index.html. Every point's result is kept in a results store (reports/result_store.h)
// under a key of what determines it, and a sweep measures only the points the store lacks: in this
// process, in --jobs N child processes, or as the tasks of a Slurm job array or of GNU parallel
// (--emit slurm|parallel DIR; reports/sweep_tasks.h), whose results --collect DIR merges in sweep
// order. The CSV is the same bytes whichever way its points were measured (docs/cluster.md).
#pragma once
#include <string>

namespace tex {

// The command line of `texsim explore`, as given (lists are comma-separated).
struct ExploreArgs {
  std::string scenes = "plane";
  std::string queries;  // a query trace instead of scenes
  std::string model, scene_file;  // a textured 3D model or a scene file instead (its first frame, orbit camera or `camera`)
  std::string camera;
  std::string texture = "testcard:1024x1024";
  std::string filter = "trilinear";
  int width = 640, height = 480, tile = 8;
  std::string orders = "scanline,tiled";
  std::string formats = "rgba8";  // how memory holds the textures (model/block_formats.h)
  std::string cache_kib = "2,4,8,16,32";
  std::string ways = "2";
  std::string blocks = "4x4,8x8";
  std::string block_orders = "row-major";
  std::string latencies = "50,100,200,400,800";
  std::string bandwidths = "16";
  std::string fifo_depths = "max";
  std::string timing = "model";  // model | rtl | none
  std::string confirm;           // "" | rtl
  std::string out_dir = "out/explore";
  std::string store_dir;        // the results store ("": default_store_dir())
  std::string emit_scheduler;   // --emit slurm|parallel DIR: write the tasks for a scheduler
  std::string emit_dir;
  int throttle = 0;             // Slurm: tasks at once (0: no limit)
  std::string sshloginfile;     // GNU parallel: the hosts
  std::string collect_dir;      // merge an emitted sweep's results from the store
  std::string task_fingerprint; // --task FINGERPRINT: measure into the store only (what a task runs)
  int jobs = 1;
  bool plots = true;
};

// Runs the command; `self` is the path of this executable (child jobs run it). Throws tex::Error.
int run_explore(const ExploreArgs& args, const std::string& self);

}  // namespace tex
