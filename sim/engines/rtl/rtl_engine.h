// `texsim --engine rtl`: the requests through the Verilated tex_unit, in the smallest compiled
// configuration that holds the texture, driven by rtl::Driver with the --stalls timing.
#pragma once
#include <memory>

#include "engines/engine.h"

namespace tex::rtl {

std::unique_ptr<Engine> make_rtl_engine(const EngineOptions& options);

}  // namespace tex::rtl
