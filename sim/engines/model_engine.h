// The golden model as an engine (--engine model): every sample by the model's Sampler, and, unless
// --no-timing, every response's clock by the timing model clocked like the smallest compiled RTL
// configuration that takes the frame (engines/rtl/configs.h), or the design's defaults. run_model
// (engine.h) is its work.
#pragma once
#include <memory>

#include "engines/engine.h"

namespace tex {

std::unique_ptr<Engine> make_model_engine(const EngineOptions& options);

}  // namespace tex
