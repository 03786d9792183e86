// The engines of this build.
#include "engines/engine.h"
#include "engines/model_engine.h"
#include "engines/rtl/rtl_engine.h"
#include "engines/systemc/systemc_engine.h"
#include "model/error.h"

namespace tex {

const std::vector<EngineInfo>& engines() {
  static const std::vector<EngineInfo> list = {
      {"model", "the golden model (bit-exact executable specification)", false, false,
       make_model_engine},
      {"rtl", "the Verilated RTL, cycle-accurate, smallest configuration that holds the texture", true, true,
       rtl::make_rtl_engine},
      {"systemc", "the Verilated RTL behind a TLM-2.0 socket (approximately timed, pipelined)", true, true,
       [](const EngineOptions& o) { return systemc::make_systemc_engine(systemc::Backend::Rtl, o); }},
      {"systemc-model", "the golden model behind the same socket (loosely timed)", false, false,
       [](const EngineOptions& o) { return systemc::make_systemc_engine(systemc::Backend::Model, o); }},
  };
  return list;
}

std::string engine_list() {
  std::string s;
  for (const EngineInfo& e : engines()) s += (s.empty() ? "" : " | ") + e.name;
  return s;
}

const EngineInfo& engine_info(const std::string& name) {
  for (const EngineInfo& e : engines())
    if (e.name == name) return e;
  throw Error("unknown engine '" + name + "' (" + engine_list() + ")");
}

std::unique_ptr<Engine> make_engine(const std::string& name, const EngineOptions& options) {
  const EngineInfo& info = engine_info(name);
  if (!options.trace_path.empty() && !info.can_trace)
    throw Error("--trace: engine " + name + " cannot write waveforms (use --engine rtl)");
  return info.make(options);
}

}  // namespace tex
