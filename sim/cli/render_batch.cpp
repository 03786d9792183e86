#include "cli/render_batch.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "model/error.h"
#include "reports/sweep_tasks.h"
#include "workloads/output_files.h"

namespace tex {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMagic = "texsim render batch 1";

// frames/STEM_FFF.EXT and frames/STEM_FFF.json
std::string frame_name(const std::string& out, int f, const std::string& ext) {
  char num[16];
  std::snprintf(num, sizeof num, "_%03d", f);
  return fs::path(out).stem().string() + num + ext;
}

}  // namespace

std::vector<std::string> render_task_arguments(const std::vector<std::string>& in) {
  // Options with one value the batch sets per frame (--out, --stats, --frame) or owns; --emit has two.
  const std::map<std::string, int> drop = {{"--emit", 2},     {"--out", 1},          {"-o", 1},
                                           {"--stats", 1},    {"--frame", 1},        {"--throttle", 1},
                                           {"--sshloginfile", 1}, {"--frames-per-task", 1}};
  std::vector<std::string> out;
  for (size_t i = 0; i < in.size(); ++i) {
    const std::string& w = in[i];
    const size_t eq = w.find('=');
    const std::string name = w.rfind("--", 0) == 0 && eq != std::string::npos ? w.substr(0, eq) : w;
    const auto it = drop.find(name);
    if (it == drop.end()) {
      out.push_back(w);
      continue;
    }
    i += size_t(it->second) - (name != w ? 1 : 0);  // (--name=value carries its first value)
  }
  return out;
}

int emit_render_batch(const RenderBatchArgs& a) {
  EmitOptions o;
  o.scheduler = parse_scheduler(a.scheduler);
  o.dir = fs::absolute(a.dir).string();
  o.throttle = a.throttle;
  o.sshloginfile = a.sshloginfile;
  o.job_name = "texsim-render";
  o.collect = "texsim render --collect " + shell_quote(o.dir);
  if (a.frames < 1) throw Error("--frames " + std::to_string(a.frames) + " must be at least 1");
  if (a.frames_per_task < 1) throw Error("--frames-per-task " + std::to_string(a.frames_per_task) + " must be at least 1");
  check_emit_options(o);
  const std::string ext = fs::path(a.out).extension().string();
  if (ext.empty()) throw Error("--out " + a.out + ": no extension to name the frames' pictures by (.png, .exr, ...)");
  const fs::path frames_dir = fs::path(o.dir) / "frames";
  // Each task: cd to here (the arguments' relative paths), then its frames one after another.
  const std::string cd = "cd " + shell_quote(fs::current_path().string()) + " && ";
  std::vector<std::string> lines;
  std::string manifest = std::string(kMagic) + "\nscheduler " + scheduler_name(o.scheduler) + "\n";
  const int tasks = (a.frames + a.frames_per_task - 1) / a.frames_per_task;
  manifest += "tasks " + std::to_string(tasks) + "\nframes " + std::to_string(a.frames) + "\n";
  for (int t = 0; t < tasks; ++t) {
    std::string line = cd;
    for (int f = t * a.frames_per_task; f < std::min(a.frames, (t + 1) * a.frames_per_task); ++f) {
      const std::string picture = (frames_dir / frame_name(a.out, f, ext)).string();
      const std::string stats = (frames_dir / frame_name(a.out, f, ".json")).string();
      std::vector<std::string> argv = {a.self, "render"};
      argv.insert(argv.end(), a.args.begin(), a.args.end());
      argv.insert(argv.end(), {"--frame", std::to_string(f), "--out", picture, "--stats", stats});
      line += (f == t * a.frames_per_task ? "" : " && ") + shell_line(argv);
      manifest += std::to_string(t) + "\t" + picture + "\t" + stats + "\n";
    }
    lines.push_back(line);
  }
  prepare_emit_dir(a.dir);
  std::error_code ec;  // (the frames of an earlier batch in this directory)
  for (const auto& e : fs::directory_iterator(frames_dir, ec))
    if (e.is_regular_file(ec)) fs::remove(e.path(), ec);
  o.manifest_name = "render.txt";
  o.manifest = manifest;
  emit_task_lines(o, lines);
  fs::create_directories(frames_dir, ec);
  if (!fs::is_directory(frames_dir, ec)) throw Error("--emit: cannot create " + frames_dir.string());
  std::printf("texsim render: %d frames in %d tasks -> %s (%s); then texsim render --collect %s\n", a.frames, tasks,
              o.dir.c_str(), emit_hint(o).c_str(), a.dir.c_str());
  return 0;
}

int collect_render_batch(const std::string& dir) {
  const fs::path path = fs::path(dir) / "render.txt";
  std::ifstream in(path);
  if (!in) throw Error("--collect: " + path.string() + " does not exist (emit the frames with render --frames N --emit slurm|parallel " + dir + " first)");
  std::string line;
  size_t n = 1;
  auto bad = [&](const std::string& why) { throw Error("--collect: " + path.string() + " line " + std::to_string(n) + ": " + why); };
  if (!std::getline(in, line) || line != kMagic) bad(std::string("not a texsim render batch (\"") + kMagic + "\")");
  auto field = [&](const std::string& name) {
    ++n;
    if (!std::getline(in, line) || line.rfind(name + " ", 0) != 0) bad("expected `" + name + " ...`");
    return line.substr(name.size() + 1);
  };
  const Scheduler scheduler = parse_scheduler(field("scheduler"));
  const size_t tasks = std::stoul(field("tasks")), frames = std::stoul(field("frames"));
  nlohmann::json all = nlohmann::json::array();
  std::map<size_t, size_t> missing;  // task -> frames missing
  size_t f = 0;
  for (; std::getline(in, line); ++f) {
    ++n;
    const size_t a = line.find('\t'), b = a == std::string::npos ? a : line.find('\t', a + 1);
    if (b == std::string::npos) bad("not task<TAB>picture<TAB>stats");
    const size_t task = std::stoul(line.substr(0, a));
    const std::string picture = line.substr(a + 1, b - a - 1), stats = line.substr(b + 1);
    std::error_code ec;
    nlohmann::json s;
    std::ifstream sf(stats);
    const bool ok = fs::is_regular_file(picture, ec) && fs::file_size(picture, ec) > 0 && sf &&
                    (s = nlohmann::json::parse(sf, nullptr, false), s.is_object());
    if (!ok) {
      ++missing[task];
      continue;
    }
    all.push_back({{"frame", f}, {"picture", picture}, {"stats", s}});
  }
  if (f != frames) bad("ends after " + std::to_string(f) + " of " + std::to_string(frames) + " frames");
  if (!missing.empty()) fail_collect(dir, scheduler, missing, frames, tasks, "frames", "texsim render --collect " + dir);
  OutputSet outputs;
  OutputFile& out = outputs.declare((fs::path(dir) / "frames.json").string(), "--collect");
  const std::string text = nlohmann::json{{"frames", all}}.dump(1) + "\n";
  std::fputs(text.c_str(), out.open());
  out.close();
  outputs.commit();
  uint64_t samples = 0;
  for (const auto& fr : all) samples += fr["stats"].value("samples", uint64_t(0));
  std::printf("texsim render: collected %zu frames of %zu tasks (%llu samples) into %s/frames.json; pictures in %s/frames\n",
              frames, tasks, static_cast<unsigned long long>(samples), dir.c_str(), dir.c_str());
  return 0;
}

}  // namespace tex
