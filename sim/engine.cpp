#include "engine.h"

#include "model/error.h"
#ifdef TEXSIM_HAVE_RTL
#include "rtl/rtl_engine.h"
#endif
#ifdef TEXSIM_HAVE_SYSTEMC
#include "systemc/systemc_engine.h"
#endif

namespace tex {

const std::vector<std::string>& engine_names() {
  static const std::vector<std::string> names = {
      "model",
#ifdef TEXSIM_HAVE_RTL
      "rtl",
#endif
#ifdef TEXSIM_HAVE_SYSTEMC
      "systemc",        // TLM-2.0 socket in front of the Verilated RTL (approximately timed)
      "systemc-model",  // the same socket in front of the golden model (loosely timed)
#endif
  };
  return names;
}

EngineResult run_model(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests) {
  Sampler sampler(pyramid, config);
  EngineResult r;
  r.texels.reserve(requests.size());
  for (const Request& q : requests) r.texels.push_back(sampler.sample(q));
  const SamplerStats s = sampler.stats();
  nlohmann::json banks = nlohmann::json::array();
  for (const auto& lvl : s.memory.bank_reads) banks.push_back(lvl);
  r.stats = {{"engine", "model"},
             {"samples", s.samples},
             {"texel_reads", s.memory.reads},
             {"multiplies_per_channel", s.multiplies_per_channel},
             {"bank_reads", banks}};
  return r;
}

EngineResult run_engine(const std::string& engine, const Pyramid& pyramid, const SamplerConfig& config,
                        const std::vector<Request>& requests, const EngineOptions& options) {
  if (engine == "model") return run_model(pyramid, config, requests);
#ifdef TEXSIM_HAVE_RTL
  if (engine == "rtl") return rtl::run_rtl(pyramid, config, requests, options);
#endif
#ifdef TEXSIM_HAVE_SYSTEMC
  if (engine == "systemc")
    return systemc::run_systemc(pyramid, config, requests, systemc::systemc_options_for(systemc::Backend::Rtl, options));
  if (engine == "systemc-model")
    return systemc::run_systemc(pyramid, config, requests,
                                systemc::systemc_options_for(systemc::Backend::Model, options));
#endif
  (void)options;
  std::string list;
  for (const auto& n : engine_names()) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown engine '" + engine + "' (this build has: " + list + ")");
}

}  // namespace tex
