// tex_cache_tags: the tags of one texture cache (docs/memory.md §2): LINES lines in SETS =
// 2^cfg_log2_sets sets of 2^cfg_log2_ways ways, true LRU. Split into 4 banks by the set's two low
// bits (the block's x and y parities): bank p answers one lookup per clock, so the at most four
// blocks of one level's 2x2 footprint are looked up in one clock.
// Bank p holds entry ((set >> 2) << log2_ways) | way of every set with set & 3 = p; the same
// index, with the set's low bits, is the line's slot in the data banks (tex_cache_data):
//   slot = (set << log2_ways) | way.
// Handshake: none. Lookup: combinational from look_*; the update (on a hit: LRU; on a miss: the
//   victim's tag, valid and LRU) happens at the clock edge when en && look_valid[p]. Reset (rst)
//   invalidates every line and sets each way's age to its way number (in one clock, by marking
//   every row of valid bits and ages as not yet written); cfg_log2_* must then be the values
//   used until the next reset.
// Latency: 0 (lookup) / 1 (update). Throughput: 4 lookups per clock, one per bank.
// Ports:
//   cfg_log2_sets, cfg_log2_ways : integers; 4 <= sets, sets * ways <= LINES, ways <= MAX_WAYS
//   look_valid[p] : bank p looks up a line in this clock (its block has parities p)
//   look_set_hi   : bank p's set >> 2 at [p*SHW +: SHW]
//   look_line     : bank p's line number (line address / line bytes) at [p*LNW +: LNW]
//   hit[p]        : the line is in the cache (0 when bank p does not look up)
//   slot          : bank p's line slot at [p*SLW +: SLW] (the hit way or the victim way; 0 when
//                   bank p does not look up)
`include "tex_param_error.svh"
module tex_cache_tags #(
  parameter int LINES    = 128,  // lines per cache (power of two, >= 4 * MAX_WAYS)
  parameter int MAX_WAYS = 4,    // 1, 2 or 4
  parameter int LNW      = 26,   // bits of a line number
  parameter int SLW      = $clog2(LINES),             // derived: bits of a line slot
  parameter int SHW      = (SLW > 2) ? SLW - 2 : 1    // derived: bits of set >> 2
) (
  input  logic                                clk,
  input  logic                                rst,
  input  logic                                en,
  input  logic [tex_pkg::LOG2_SETS_W-1:0]     cfg_log2_sets,
  input  logic [tex_pkg::LOG2_WAYS_W-1:0]     cfg_log2_ways,
  input  logic [3:0]                          look_valid,
  input  logic [4*SHW-1:0]                    look_set_hi,
  input  logic [4*LNW-1:0]                    look_line,
  output logic [3:0]                          hit,
  output logic [4*SLW-1:0]                    slot
);
  /*verilator inline_module*/  // (else too large for Verilator's default: a C++ call per instance)
  localparam int BANK = LINES / 4;           // entries per bank
  localparam int EW   = (SLW > 2) ? SLW - 2 : 1;  // bits of a bank entry index
  localparam int AGW  = 2;                   // age bits (MAX_WAYS <= 4)
  // A bank's valid bits and LRU ages are kept per row of MAX_WAYS entries (a set's ways are in
  // one row: its base is a multiple of ways, which divides MAX_WAYS): one array word per row,
  // {ages, valid bits}, rewritten by a lookup. A row never written since reset reads as reset
  // (row_ok clear): invalid, each way's age its way number. Per-row words rather than packed
  // vectors of all the bank's bits: Verilator copies a wide register into a delayed-write
  // shadow in every clock, and writes one array word through three small temporaries.
  localparam int LMW  = $clog2(MAX_WAYS);    // log2 entries per row
  localparam int ROWS = BANK / MAX_WAYS;
  localparam int RW   = (ROWS > 1) ? $clog2(ROWS) : 1;  // bits of a row index
  localparam int MW   = MAX_WAYS * (1 + AGW);          // a row word: ages at [MAX_WAYS + pos*AGW]

  generate
    if (LINES < 4 * MAX_WAYS || (LINES & (LINES - 1)) != 0) begin : g_bad_lines
      `TEX_PARAM_ERROR("tex_cache_tags: LINES must be a power of two, at least 4 * MAX_WAYS")
    end
  endgenerate

  logic [2:0] ways;  // 1, 2 or 4
  assign ways = 3'(1) << cfg_log2_ways;
  logic [EW-1:0] set_mask;  // (sets >> 2) - 1: the set bits a bank uses
  assign set_mask = EW'((1 << (cfg_log2_sets - 2)) - 1);
  // A row at reset: no valid bit, ages = way number (entry position mod ways).
  logic [MW-1:0] row_at_reset;
  always_comb begin
    row_at_reset = '0;
    for (int e = 0; e < MAX_WAYS; e++)
      row_at_reset[MAX_WAYS + e*AGW +: AGW] = AGW'(3'(e) & (ways - 3'd1));
  end

  genvar p;
  generate
    for (p = 0; p < 4; p = p + 1) begin : g_bank
      logic [LNW-1:0]  tag [BANK];
      logic [MW-1:0]   meta [ROWS];
      logic [ROWS-1:0] row_ok;      // the row has been written since reset

      logic [EW-1:0]  base;         // entry of way 0 of the looked-up set
      logic [RW-1:0]  row;
      logic [LNW-1:0] line;
      logic           found;
      logic [1:0]     way;          // the hit way, else the victim (age = ways - 1)
      logic [MW-1:0]  row_next;     // the row after this lookup
      logic [SLW-1:0] slot_p;
      // Only when bank p looks up (all 0 otherwise: nothing uses them then), so that a simulator
      // skips the comparisons in the clocks without a lookup.
      always_comb begin
        logic [MW-1:0]  cur;
        logic [LMW:0]   off;        // position of way 0 in the row
        logic [31:0]    q_way;      // position of the hit or victim way in the row
        logic [AGW-1:0] way_age;
        logic [MAX_WAYS-1:0] in_set;  // the row's entries that belong to the looked-up set
        {cur, off, q_way, way_age, in_set} = '0;
        base     = '0;
        row      = '0;
        line     = '0;
        found    = 1'b0;
        way      = '0;
        row_next = '0;
        slot_p   = '0;
        if (look_valid[p]) begin
          base = (EW'(look_set_hi[p*SHW +: SHW]) & set_mask) << cfg_log2_ways;
          row  = RW'(base >> LMW);
          off  = (LMW+1)'(base) & (LMW+1)'(MAX_WAYS - 1);
          cur  = row_ok[row] ? meta[row] : row_at_reset;
          line = look_line[p*LNW +: LNW];
          // Every entry q of the row, those of the looked-up set (q & ~(ways - 1) = off) only:
          // constant selects, no shifter. Way w of the set is entry q = off | w. The lowest way
          // wins (as the model's scan): the victim (the one way with age ways - 1), then a hit.
          for (int q = 0; q < MAX_WAYS; q++) in_set[q] = (32'(q) & ~(32'(ways) - 1)) == 32'(off);
          way_age = AGW'(ways - 3'd1);
          for (int q = MAX_WAYS - 1; q >= 0; q--) begin
            if (in_set[q] && cur[MAX_WAYS + q*AGW +: AGW] == AGW'(ways - 3'd1)) q_way = 32'(q);
          end
          for (int q = MAX_WAYS - 1; q >= 0; q--) begin
            if (in_set[q] && cur[q] && tag[(base & ~EW'(MAX_WAYS - 1)) | EW'(q)] == line) begin
              found   = 1'b1;
              q_way   = 32'(q);
              way_age = cur[MAX_WAYS + q*AGW +: AGW];
            end
          end
          way      = 2'(q_way) & 2'(ways - 3'd1);
          row_next = cur;
          for (int q = 0; q < MAX_WAYS; q++) begin  // LRU: the way used becomes 0, younger ones age
            if (in_set[q]) begin
              if (32'(q) == q_way) begin
                row_next[MAX_WAYS + q*AGW +: AGW] = '0;
                row_next[q] = 1'b1;  // a miss fills the victim way
              end else if (cur[MAX_WAYS + q*AGW +: AGW] < way_age) begin
                row_next[MAX_WAYS + q*AGW +: AGW] = cur[MAX_WAYS + q*AGW +: AGW] + 1'b1;
              end
            end
          end
          slot_p = (SLW'({EW'(look_set_hi[p*SHW +: SHW]) & set_mask, 2'(p)}) << cfg_log2_ways)
                 | SLW'(way);
        end
      end
      assign hit[p] = found;
      assign slot[p*SLW +: SLW] = slot_p;

      always_ff @(posedge clk) begin
        if (rst) begin
          row_ok <= '0;
        end else if (en && look_valid[p]) begin
          meta[row]   <= row_next;
          row_ok[row] <= 1'b1;
          if (!found) tag[base | EW'(way)] <= line;
        end
      end
    end
  endgenerate
endmodule
