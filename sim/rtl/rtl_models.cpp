// The configuration-specific part of the harness: one template over the Verilated class, one
// instance per compiled configuration (sim/CMakeLists.txt verilates tex_unit with -G parameters
// and a distinct --prefix for each).
#include <verilated.h>
#include <verilated_fst_c.h>

#include <memory>
#include <type_traits>

#include "Vtex_unit_10x10.h"
#include "Vtex_unit_4x4.h"
#include "Vtex_unit_6x3.h"
#include "Vtex_unit_5x4_cw16.h"
#include "model/error.h"
#include "rtl_harness.h"

namespace tex::rtl {

namespace {

template <class Top>
class VerilatedTexUnit final : public Harness {
 public:
  VerilatedTexUnit(const RtlShape& shape, const HarnessOptions& options) : Harness(shape, options) {
    context_ = std::make_unique<VerilatedContext>();
    context_->fatalOnError(false);  // an assertion sets gotFinish; tick() closes the trace and throws
    // Registers without reset start random (from the seed): the design must not depend on them.
    context_->randReset(2);
    context_->randSeed(int(options.seed & 0x7fffffff));
    if (tracing_) context_->traceEverOn(true);
    top_ = std::make_unique<Top>(context_.get(), "tex_unit");
    if (tracing_) {
      trace_ = std::make_unique<VerilatedFstC>();
      top_->trace(trace_.get(), 99);
      trace_->open(options.trace_path.c_str());
      if (!trace_->isOpen()) throw Error("cannot open FST trace '" + options.trace_path + "'");
    }
    top_->clk = 1;
    top_->rst = 1;
    top_->eval();
  }

  ~VerilatedTexUnit() override {
    close_trace();
    top_->final();
  }

 protected:
  PinsOut tick_pins(const PinsIn& in, bool dump) override {
    Top& t = *top_;
    t.rst = in.rst;
    t.wr_en = in.wr_en;
    t.wr_level = in.wr_level;
    t.wr_x = in.wr_x;
    t.wr_y = in.wr_y;
    t.wr_data = std::remove_reference_t<decltype(t.wr_data)>(in.wr_data);  // 32 or 64 bits: 4 * CW
    t.req_valid = in.req_valid;
    t.req_u = uint32_t(in.req_u);
    t.req_v = uint32_t(in.req_v);
    t.req_lod = uint16_t(in.req_lod);
    t.req_tag = in.req_tag;
    t.rsp_ready = in.rsp_ready;
    t.clk = 0;
    t.eval();
    const uint64_t time = 2 * cycle();
    if (dump) trace_->dump(time);
    PinsOut out;
    out.req_ready = t.req_ready;
    out.rsp_valid = t.rsp_valid;
    out.rsp_rgba = t.rsp_rgba;
    out.rsp_tag = t.rsp_tag;
    t.clk = 1;
    t.eval();
    if (dump) trace_->dump(time + 1);
    return out;
  }

  void apply_cfg(const CfgPins& c) override {
    Top& t = *top_;
    t.cfg_log2_w = c.log2_w;
    t.cfg_log2_h = c.log2_h;
    t.cfg_wrap_u = c.wrap_u;
    t.cfg_wrap_v = c.wrap_v;
    t.cfg_texel_linear = c.texel_linear;
    t.cfg_mip_mode = c.mip_mode;
    t.cfg_lod_bias = uint16_t(c.lod_bias);
    t.cfg_min_lod = uint16_t(c.min_lod);
    t.cfg_max_lod = uint16_t(c.max_lod);
    t.eval();
  }

  bool got_finish() const override { return context_->gotFinish(); }

  void close_trace_impl() override {
    if (trace_) {
      trace_->close();
      trace_.reset();
    }
  }

 private:
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Top> top_;
  std::unique_ptr<VerilatedFstC> trace_;
};

}  // namespace

const std::vector<RtlShape>& compiled_shapes() {
  static const std::vector<RtlShape> shapes = {
      {"Vtex_unit_4x4", 4, 4, 8}, {"Vtex_unit_6x3", 6, 3, 8}, {"Vtex_unit_10x10", 10, 10, 8},
      {"Vtex_unit_5x4_cw16", 5, 4, 16}};
  return shapes;
}

std::unique_ptr<Harness> Harness::create(const RtlShape& shape, const HarnessOptions& options) {
  if (shape.name == "Vtex_unit_4x4") return std::make_unique<VerilatedTexUnit<Vtex_unit_4x4>>(shape, options);
  if (shape.name == "Vtex_unit_6x3") return std::make_unique<VerilatedTexUnit<Vtex_unit_6x3>>(shape, options);
  if (shape.name == "Vtex_unit_5x4_cw16")
    return std::make_unique<VerilatedTexUnit<Vtex_unit_5x4_cw16>>(shape, options);
  if (shape.name == "Vtex_unit_10x10") return std::make_unique<VerilatedTexUnit<Vtex_unit_10x10>>(shape, options);
  throw Error("no compiled RTL configuration named '" + shape.name + "'");
}

}  // namespace tex::rtl
