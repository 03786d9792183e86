// tex_axi_read: the cached unit's AXI4 read master (AMBA AXI4 names): tex_cached_fetch's line
// reads (mem_req, from the miss ring) and line beats (mem_rsp, into the fill FIFO) as the AR and
// R channels. One INCR burst per cache line: LINE_BITS / MEM_W beats of MEM_W bits (ARLEN =
// beats - 1, ARSIZE = log2 of the beat's bytes), a single ID (ARID = 0) and so responses in order.
// RRESP SLVERR or DECERR is mem_rsp_error (RRESP[1]); OKAY and EXOKAY are not. RLAST and RID
// carry nothing the unit needs (it counts the beats); simulation checks them, and that the
// manager side keeps the protocol (ARVALID held with ARADDR until ARREADY).
// Handshake: AR = mem_req, R = mem_rsp, valid/ready wire for wire (no register, no combinational
//   path added). Latency: 0. Throughput: one read request and one beat per clock.
// Ports:
//   mem_req_addr, m_axi_araddr : byte address of a line, line aligned (tex_pkg::MEM_ADDR_W bits)
//   mem_rsp_data, m_axi_rdata  : one beat: bytes [i*MEM_W/8 +: MEM_W/8] of the line in beat i
`include "tex_param_error.svh"
module tex_axi_read #(
  parameter int MEM_W     = 128,  // AXI data width: bits of a beat (32..256, divides the line)
  parameter int LINE_BITS = 512,
  parameter int AXI_ID_W  = 1     // 1..16; the unit reads with ID 0
) (
  input  logic                           clk,
  input  logic                           rst,
  input  logic                           mem_req_valid,
  output logic                           mem_req_ready,
  input  logic [tex_pkg::MEM_ADDR_W-1:0] mem_req_addr,
  output logic                           mem_rsp_valid,
  input  logic                           mem_rsp_ready,
  output logic [MEM_W-1:0]               mem_rsp_data,
  output logic                           mem_rsp_error,

  output logic                           m_axi_arvalid,
  input  logic                           m_axi_arready,
  output logic [tex_pkg::MEM_ADDR_W-1:0] m_axi_araddr,
  output logic [7:0]                     m_axi_arlen,
  output logic [2:0]                     m_axi_arsize,
  output logic [1:0]                     m_axi_arburst,
  output logic [AXI_ID_W-1:0]            m_axi_arid,
  output logic [3:0]                     m_axi_arcache,
  output logic [2:0]                     m_axi_arprot,
  input  logic                           m_axi_rvalid,
  output logic                           m_axi_rready,
  input  logic [MEM_W-1:0]               m_axi_rdata,
  input  logic [1:0]                     m_axi_rresp,
  input  logic                           m_axi_rlast,
  input  logic [AXI_ID_W-1:0]            m_axi_rid
);
  localparam int BEATS = LINE_BITS / MEM_W;
  generate
    if (MEM_W < 32 || MEM_W > 256 || (MEM_W & (MEM_W - 1)) != 0 || LINE_BITS % MEM_W != 0
        || BEATS > 256) begin : g_bad_mem_w
      `TEX_PARAM_ERROR("tex_axi_read: parameter MEM_W must be a power of two from 32 to 256 that divides LINE_BITS in at most 256 beats")
    end
    if (AXI_ID_W < 1 || AXI_ID_W > 16) begin : g_bad_axi_id_w
      `TEX_PARAM_ERROR("tex_axi_read: parameter AXI_ID_W must be in 1..16")
    end
  endgenerate

  assign m_axi_arvalid = mem_req_valid;
  assign mem_req_ready = m_axi_arready;
  assign m_axi_araddr  = mem_req_addr;
  assign m_axi_arlen   = 8'(BEATS - 1);
  assign m_axi_arsize  = 3'($clog2(MEM_W / 8));
  assign m_axi_arburst = 2'b01;      // INCR
  assign m_axi_arid    = '0;
  assign m_axi_arcache = 4'b0011;    // normal, non-cacheable, bufferable
  assign m_axi_arprot  = 3'b000;     // unprivileged, secure, data
  assign mem_rsp_valid = m_axi_rvalid;
  assign m_axi_rready  = mem_rsp_ready;
  assign mem_rsp_data  = m_axi_rdata;
  assign mem_rsp_error = m_axi_rresp[1];  // SLVERR (10) or DECERR (11)
  logic rlast_unused;                // checked in simulation below: the beats are counted
  logic [AXI_ID_W-1:0] rid_unused;   // one ID: responses in order
  logic rresp_exokay_unused;         // RRESP[0] tells OKAY from EXOKAY (no exclusive reads)
  assign rlast_unused = m_axi_rlast;
  assign rid_unused   = m_axi_rid;
  assign rresp_exokay_unused = m_axi_rresp[0];

`ifndef SYNTHESIS
  logic                           mreq_stalled_q;
  logic [31:0]                    r_beat, bursts_open;
  logic [tex_pkg::MEM_ADDR_W-1:0] mreq_addr_q;
  always_ff @(posedge clk) begin
    mreq_stalled_q <= !rst && m_axi_arvalid && !m_axi_arready;
    if (m_axi_arvalid && !m_axi_arready) mreq_addr_q <= m_axi_araddr;
    if (rst) begin
      r_beat      <= '0;
      bursts_open <= '0;
    end else begin
      if (m_axi_rvalid && m_axi_rready) begin
        assert (bursts_open != '0 || (m_axi_arvalid && m_axi_arready))
          else $error("tex_axi_read: an AXI read beat with no burst outstanding");
        assert (m_axi_rlast == (r_beat == 32'(BEATS - 1)))
          else $error("tex_axi_read: RLAST %0d on beat %0d of a burst of %0d", m_axi_rlast, r_beat, BEATS);
        assert (m_axi_rid == '0) else $error("tex_axi_read: RID %0d, the unit reads with ID 0", m_axi_rid);
        r_beat <= (r_beat == 32'(BEATS - 1)) ? '0 : r_beat + 1;
      end
      bursts_open <= bursts_open + 32'(m_axi_arvalid && m_axi_arready)
                   - 32'(m_axi_rvalid && m_axi_rready && r_beat == 32'(BEATS - 1));
    end
    if (!rst && mreq_stalled_q) begin
      assert (m_axi_arvalid && m_axi_araddr == mreq_addr_q)
        else $error("tex_axi_read: ARVALID dropped or ARADDR changed while ARREADY was low");
    end
  end
`endif
endmodule
