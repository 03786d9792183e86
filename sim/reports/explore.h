// `texsim explore`: sweeps the cached memory hierarchy over workloads (docs/memory.md §6).
//
// A sweep is the cartesian product of its lists: workload (scene or query trace) x rasterization
// order x cache size x ways x block shape x block order x memory latency x bandwidth x FIFO depth.
// Every point gets one CSV row. Hit rate and bytes per sample come from the golden model's caches;
// samples per clock from the Verilated RTL wherever a compiled configuration holds the point (its
// block shape, cache size and FIFO depth), else the row is the model's alone (timing_engine empty).
// Through the RTL the model's caches still run alongside and every line the RTL reads is checked
// against them, so the two engines' hit counts are one and the same.
//
// Outputs in OUT: explore.csv, then scripts/explore_plots.py's latency.png, hit_rate.png,
// bytes.png and index.html. Points run in this process, or in --jobs N child processes, or as
// command lines for a cluster (--emit-jobs FILE) whose row files --collect OUT merges.
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
  std::string cache_kib = "2,4,8,16,32";
  std::string ways = "2";
  std::string blocks = "4x4,8x8";
  std::string block_orders = "row-major";
  std::string latencies = "50,100,200,400,800";
  std::string bandwidths = "16";
  std::string fifo_depths = "max";
  std::string timing = "rtl";  // rtl | none
  std::string out_dir = "out/explore";
  std::string rows_path;       // measure here and write only these rows (a job of --emit-jobs)
  std::string emit_jobs_path;  // write one command line per job instead of running them
  std::string collect_dir;     // merge the row files of emitted jobs
  int jobs = 1;
  bool plots = true;
};

// Runs the command; `self` is the path of this executable (child jobs run it). Throws tex::Error.
int run_explore(const ExploreArgs& args, const std::string& self);

}  // namespace tex
