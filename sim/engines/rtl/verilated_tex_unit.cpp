// The configuration-specific part of the driver: one template over the Verilated class, one
// instance per compiled configuration. The list of configurations comes from the generated
// rtl_configs.h (declared once, in sim/engines/rtl/CMakeLists.txt).
#include <verilated.h>
#include <verilated_fst_c.h>
#include <verilated_syms.h>

#include <cstring>
#include <memory>
#include <type_traits>

#include "engines/rtl/driver.h"
#include "model/error.h"
#include "rtl_configs.h"  // generated: #include "Vtex_unit_*.h" and TEX_RTL_CONFIGS(X)

namespace tex::rtl {

namespace {

// A beat of the memory port into a Verilated input of MEM_W bits (an integer or a VlWide).
template <class Pin>
void set_beat(Pin& pin, const uint8_t* bytes) {
  if constexpr (std::is_integral_v<Pin>) {
    Pin v = 0;
    if (bytes) std::memcpy(&v, bytes, sizeof v);  // little-endian host: byte 0 in the low bits
    pin = v;
  } else if (bytes) {
    std::memcpy(pin.data(), bytes, sizeof pin);
  }
}

template <class Top>
class VerilatedTexUnit final : public Driver {
  static constexpr bool kCached = requires(Top& t) { t.m_axi_arvalid; };

 public:
  VerilatedTexUnit(const RtlConfig& config, const DriverOptions& options) : Driver(config, options) {
    context_ = std::make_unique<VerilatedContext>();
    context_->fatalOnError(false);  // an assertion sets gotFinish; tick() closes the trace and throws
    // Registers without reset start random (from the seed): the design must not depend on them.
    context_->randReset(2);
    context_->randSeed(int(options.seed & 0x7fffffff));
    if (tracing_) context_->traceEverOn(true);
    Verilated::threadContextp(context_.get());
    top_ = std::make_unique<Top>(context_.get(), "tex_unit");
    if (tracing_) {
      trace_ = std::make_unique<VerilatedFstC>();
      top_->trace(trace_.get(), 99);
      trace_->open(options.trace_path.c_str());
      if (!trace_->isOpen()) throw Error("cannot open FST trace '" + options.trace_path + "'");
    }
    if constexpr (kCached) {
      find_statistics();
      apply_descriptor(DescriptorPins{}, false);  // no write until one is asked for (the pins start random)
      apply_sampler(SamplerPins{}, false);
    } else {
      find_banks();
    }
    top_->clk = 1;
    top_->rst = 1;
    top_->eval();
  }

  ~VerilatedTexUnit() override {
    close_trace();
    current().final();
    top_.reset();  // (its scopes leave the thread's context: this unit's, current() made it so)
  }

 private:
  // The model, its context made the thread's first. Verilator 5.006 keeps one context per thread
  // (Verilated::threadContextp), not per model: a model registers and erases its scopes there, and
  // an assertion ($error, $fatal) sets gotFinish there. With several units in one process (a
  // check beside the engine, a benchmark's units one after another) it must be this unit's, else
  // an assertion of this unit goes unseen and its destructor reads a context that may be gone.
  Top& current() {
    Verilated::threadContextp(context_.get());
    return *top_;
  }

 protected:
  PinsOut tick_pins(const PinsIn& in, bool dump) override {
    Top& t = current();
    t.rst = in.rst;
    if constexpr (kCached) {
      t.m_axi_arready = in.ar_ready;
      t.m_axi_rvalid = in.r_valid;
      set_beat(t.m_axi_rdata, in.r_data);
      t.m_axi_rresp = in.r_resp;
      t.m_axi_rlast = in.r_last;
      t.m_axi_rid = 0;
      t.req_tex = in.req_tex;
      t.req_sampler = in.req_sampler;
      t.req_layer = uint32_t(in.req_layer);
      t.req_w = uint32_t(in.req_w);
      t.req_dwdx = uint32_t(in.req_dwdx);
      t.req_dwdy = uint32_t(in.req_dwdy);
    } else {
      t.wr_en = in.wr_en;
      t.wr_level = in.wr_level;
      t.wr_x = in.wr_x;
      t.wr_y = in.wr_y;
      t.wr_data = std::remove_reference_t<decltype(t.wr_data)>(in.wr_data);  // 32 or 64 bits: 4 * CW
    }
    t.req_valid = in.req_valid;
    t.req_u = uint32_t(in.req_u);
    t.req_v = uint32_t(in.req_v);
    t.req_lod = uint16_t(in.req_lod);
    t.req_bias = uint16_t(in.req_bias);
    t.req_deriv = in.req_deriv;
    t.req_dudx = uint32_t(in.req_dudx);
    t.req_dvdx = uint32_t(in.req_dvdx);
    t.req_dudy = uint32_t(in.req_dudy);
    t.req_dvdy = uint32_t(in.req_dvdy);
    t.req_tag = in.req_tag;
    t.req_op = in.req_op;
    t.req_component = in.req_component;
    t.req_ref = uint32_t(in.req_ref);
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
    if constexpr (kCached) {
      out.rsp_error = t.rsp_error;
      out.desc_ready = t.cfg_desc_ready;
      out.ar_valid = t.m_axi_arvalid;
      out.ar_addr = t.m_axi_araddr;
      out.ar_len = t.m_axi_arlen;
      out.ar_size = t.m_axi_arsize;
      out.ar_burst = t.m_axi_arburst;
      out.r_ready = t.m_axi_rready;
      out.fifo_count = fifo_count_bytes_ == 1 ? *static_cast<const uint8_t*>(fifo_count_)
                       : fifo_count_bytes_ == 2 ? *static_cast<const uint16_t*>(fifo_count_)
                                                : *static_cast<const uint32_t*>(fifo_count_);
      out.head_waits = *head_waits_;
    }
    t.clk = 1;
    t.eval();
    if (dump) trace_->dump(time + 1);
    out.finished = context_->gotFinish();
    return out;
  }

  // The cfg_smp_* pins: tex_unit's one sampler, or the data of a sampler-table write.
  void set_sampler_pins(const SamplerPins& c) {
    Top& t = current();
    t.cfg_smp_wrap_u = c.wrap_u;
    t.cfg_smp_wrap_v = c.wrap_v;
    t.cfg_smp_border_rgba = c.border_rgba;
    t.cfg_smp_min_linear = c.min_linear;
    t.cfg_smp_mag_linear = c.mag_linear;
    t.cfg_smp_mip_mode = c.mip_mode;
    t.cfg_smp_lod_bias = uint16_t(c.lod_bias);
    t.cfg_smp_min_lod = uint16_t(c.min_lod);
    t.cfg_smp_max_lod = uint16_t(c.max_lod);
    t.cfg_smp_max_aniso_m1 = c.max_aniso_m1;
    t.cfg_smp_aniso_pow2 = c.aniso_pow2;
    t.cfg_smp_unnormalized = c.unnormalized;
    t.cfg_smp_reduction = c.reduction;
    t.cfg_smp_compare_op = c.compare_op;
  }

  void apply_cfg(const CfgPins& c) override {
    if constexpr (!kCached) {  // the cached unit's sizes and samplers are its tables'
      Top& t = current();
      t.cfg_w = c.w;
      t.cfg_h = c.h;
      t.cfg_last_level = c.last_level;
      set_sampler_pins(c.sampler);
      t.eval();
    }
  }

  void apply_sampler(const SamplerPins& s, bool write) override {
    if constexpr (kCached) {
      Top& t = current();
      t.cfg_smp_we = write;
      t.cfg_smp_index = s.index;
      set_sampler_pins(s);
      t.eval();
    } else {
      throw Error(config_.name + " has no sampler table");
    }
  }

  void apply_descriptor(const DescriptorPins& d, bool write) override {
    if constexpr (kCached) {
      Top& t = current();
      t.cfg_desc_we = write;
      t.cfg_desc_index = d.index;
      t.cfg_desc_base = d.base;
      t.cfg_desc_w = d.w;
      t.cfg_desc_h = d.h;
      t.cfg_desc_last_level = d.last_level;
      t.cfg_desc_format = d.format;
      t.cfg_desc_srgb = d.srgb;
      t.cfg_desc_layers_m1 = d.layers_m1;
      t.cfg_desc_cube = d.cube;
      t.eval();
    } else {
      throw Error(config_.name + " has no texture descriptors");
    }
  }

  void apply_cache_pins(const CachePins& p) override {
    if constexpr (kCached) {
      Top& t = current();
      t.cfg_block_morton = p.block_morton;
      t.cfg_log2_sets = p.log2_sets;
      t.cfg_log2_ways = p.log2_ways;
      t.cfg_fifo_limit = p.fifo_limit;
      t.eval();
    } else {
      throw Error(config_.name + " has no cache");
    }
  }

  void backdoor_write(int level, int bank, uint32_t word, uint64_t data) override {
    const Bank& b = banks_[size_t(level)][size_t(bank)];
    if (banks_[0][0].data == nullptr)
      throw Error(config_.name + ": no texel banks visible for the backdoor load (see rtl/tex_unit.vlt)");
    if (!b.data || word >= b.words)
      throw Error(config_.name + ": backdoor write to level " + std::to_string(level) + " bank " +
                  std::to_string(bank) + " word " + std::to_string(word) + " outside its memory");
    switch (b.bytes) {  // Verilator stores a DW-bit word in 1, 2, 4 or 8 bytes
      case 1: static_cast<uint8_t*>(b.data)[word] = uint8_t(data); break;
      case 2: static_cast<uint16_t*>(b.data)[word] = uint16_t(data); break;
      case 4: static_cast<uint32_t*>(b.data)[word] = uint32_t(data); break;
      case 8: static_cast<uint64_t*>(b.data)[word] = data; break;
      default: throw Error(config_.name + ": texel banks of " + std::to_string(b.bytes) + " bytes per word");
    }
  }

  uint64_t backdoor_read(int level, int bank, uint32_t word) const override {
    const Bank& b = banks_[size_t(level)][size_t(bank)];
    if (!b.data || word >= b.words)
      throw Error(config_.name + ": backdoor read of level " + std::to_string(level) + " bank " +
                  std::to_string(bank) + " word " + std::to_string(word) + " outside its memory");
    switch (b.bytes) {
      case 1: return static_cast<const uint8_t*>(b.data)[word];
      case 2: return static_cast<const uint16_t*>(b.data)[word];
      case 4: return static_cast<const uint32_t*>(b.data)[word];
      case 8: return static_cast<const uint64_t*>(b.data)[word];
      default: throw Error(config_.name + ": texel banks of " + std::to_string(b.bytes) + " bytes per word");
    }
  }

  void close_trace_impl() override {
    if (trace_) {
      trace_->close();
      trace_.reset();
    }
  }

 private:
  // Every tex_bank's storage `mem`, found by its public LEVEL and PARITY parameters
  // (rtl/tex_unit.vlt makes them visible).
  struct Bank {
    void* data = nullptr;
    uint32_t words = 0, bytes = 0;
  };
  void find_banks() {
    const int levels = std::max(config_.max_log2_w, config_.max_log2_h) + 1;
    banks_.assign(size_t(levels), {});
    for (const auto& entry : *context_->scopeNameMap()) {
      const VerilatedScope* scope = entry.second;
      const VerilatedVar* mem = scope->varFind("mem");
      const VerilatedVar* level = scope->varFind("LEVEL");
      const VerilatedVar* parity = scope->varFind("PARITY");
      if (!mem || !level || !parity) continue;
      const int k = *static_cast<const int32_t*>(level->datap());
      const int p = *static_cast<const int32_t*>(parity->datap());
      if (k < 0 || k >= levels || p < 0 || p > 3 || mem->udims() != 1)
        throw Error(config_.name + ": unexpected texel bank " + entry.first);
      banks_[size_t(k)][size_t(p)] = {mem->datap(), uint32_t(mem->elements(1)), mem->entSize()};
    }
  }

  // tex_cached_fetch's statistics signals (public_flat_rd in rtl/tex_unit.vlt).
  void find_statistics() {
    for (const auto& entry : *context_->scopeNameMap()) {
      const VerilatedScope* scope = entry.second;
      const VerilatedVar* count = scope->varFind("fifo_count");
      const VerilatedVar* waits = scope->varFind("head_waits");
      if (!count || !waits) continue;
      if (count->entSize() > sizeof(uint32_t) || waits->entSize() != 1)
        throw Error(config_.name + ": unexpected statistics signals in " + entry.first);
      fifo_count_ = count->datap();  // a CData, SData or IData: read by its size
      fifo_count_bytes_ = count->entSize();
      head_waits_ = static_cast<const uint8_t*>(waits->datap());
    }
    if (!fifo_count_) throw Error(config_.name + ": no fifo_count signal visible (see rtl/tex_unit.vlt)");
  }

  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Top> top_;
  std::unique_ptr<VerilatedFstC> trace_;
  std::vector<std::array<Bank, 4>> banks_;  // [level][parity]
  const void* fifo_count_ = nullptr;
  size_t fifo_count_bytes_ = 0;
  const uint8_t* head_waits_ = nullptr;
};

}  // namespace

std::unique_ptr<Driver> Driver::create(const RtlConfig& config, const DriverOptions& options) {
#define TEX_RTL_CONFIG_CREATE(prefix, log2_w, log2_h, cw, ...) \
  if (config.name == #prefix) return std::make_unique<VerilatedTexUnit<prefix>>(config, options);
  TEX_RTL_CONFIGS(TEX_RTL_CONFIG_CREATE)
#undef TEX_RTL_CONFIG_CREATE
  throw Error("no compiled RTL configuration named '" + config.name + "'");
}

}  // namespace tex::rtl
