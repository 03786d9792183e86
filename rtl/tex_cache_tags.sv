// tex_cache_tags: the tags of one texture cache (docs/memory.md §2): LINES lines in SETS =
// 2^cfg_log2_sets sets of 2^cfg_log2_ways ways, true LRU. Split into 4 banks by the set's two low
// bits (the block's x and y parities): bank p answers one lookup per clock, so the at most four
// blocks of one level's 2x2 footprint are looked up in one clock.
// Bank p holds entry ((set >> 2) << log2_ways) | way of every set with set & 3 = p; the same
// index, with the set's low bits, is the line's slot in the data banks (tex_cache_data):
//   slot = (set << log2_ways) | way.
// Handshake: none. Lookup: combinational from look_*; the update (on a hit: LRU; on a miss: the
//   victim's tag, valid and LRU) happens at the clock edge when en && look_valid[p]. Reset (rst)
//   invalidates every line and sets each way's age to its way number; cfg_log2_* must then be
//   the values used until the next reset.
// Latency: 0 (lookup) / 1 (update). Throughput: 4 lookups per clock, one per bank.
// Ports:
//   cfg_log2_sets, cfg_log2_ways : integers; 4 <= sets, sets * ways <= LINES, ways <= MAX_WAYS
//   look_valid[p] : bank p looks up a line in this clock (its block has parities p)
//   look_set_hi   : bank p's set >> 2 at [p*SHW +: SHW]
//   look_line     : bank p's line number (line address / line bytes) at [p*LNW +: LNW]
//   hit[p]        : the line is in the cache (0 when bank p does not look up)
//   slot          : bank p's line slot at [p*SLW +: SLW] (the hit way or the victim way; 0 when
//                   bank p does not look up)
module tex_cache_tags #(
  parameter int LINES    = 128,  // lines per cache (power of two, >= 4)
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
  localparam int BANK = LINES / 4;           // entries per bank
  localparam int EW   = (SLW > 2) ? SLW - 2 : 1;  // bits of a bank entry index
  localparam int AGW  = 2;                   // age bits (MAX_WAYS <= 4); entry e's at {e, 1'b0}

  logic [2:0] ways;  // 1, 2 or 4
  assign ways = 3'(1) << cfg_log2_ways;
  logic [EW-1:0] set_mask;  // (sets >> 2) - 1: the set bits a bank uses
  assign set_mask = EW'((1 << (cfg_log2_sets - 2)) - 1);

  // Reset ages (age = way number), for 2 and 4 ways; 1 way has age 0.
  function automatic logic [BANK*AGW-1:0] ages_at_reset(input int n);
    for (int e = 0; e < BANK; e++) ages_at_reset[e*AGW +: AGW] = AGW'(e % n);
  endfunction
  localparam logic [BANK*AGW-1:0] AGES2 = ages_at_reset(2);
  localparam logic [BANK*AGW-1:0] AGES4 = ages_at_reset(4);

  genvar p;
  generate
    for (p = 0; p < 4; p = p + 1) begin : g_bank
      logic [LNW-1:0]      tag [BANK];
      logic [BANK-1:0]     valid;   // (packed: reset in one assignment)
      logic [BANK*AGW-1:0] age;

      logic [EW-1:0]  base;         // entry of way 0 of the looked-up set
      logic [LNW-1:0] line;
      logic           found;
      logic [1:0]     way;          // the hit way, else the victim (age = ways - 1)
      logic [AGW-1:0] way_age;
      logic [SLW-1:0] slot_p;
      // Only when bank p looks up (all 0 otherwise: nothing uses them then), so that a simulator
      // skips the comparisons in the clocks without a lookup.
      always_comb begin
        base    = '0;
        line    = '0;
        found   = 1'b0;
        way     = '0;
        way_age = '0;
        slot_p  = '0;
        if (look_valid[p]) begin
          base = (EW'(look_set_hi[p*SHW +: SHW]) & set_mask) << cfg_log2_ways;
          line = look_line[p*LNW +: LNW];
          for (int w = MAX_WAYS - 1; w >= 0; w--) begin  // the victim: one way has that age
            if (3'(w) < ways && age[{base | EW'(w), 1'b0} +: AGW] == AGW'(ways - 3'd1)) way = 2'(w);
          end
          for (int w = MAX_WAYS - 1; w >= 0; w--) begin
            if (3'(w) < ways && valid[base | EW'(w)] && tag[base | EW'(w)] == line) begin
              found = 1'b1;
              way   = 2'(w);
            end
          end
          way_age = age[{base | EW'(way), 1'b0} +: AGW];
          slot_p  = (SLW'({EW'(look_set_hi[p*SHW +: SHW]) & set_mask, 2'(p)}) << cfg_log2_ways)
                  | SLW'(way);
        end
      end
      assign hit[p] = found;
      assign slot[p*SLW +: SLW] = slot_p;

      always_ff @(posedge clk) begin
        if (rst) begin
          valid <= '0;
          age   <= (ways == 3'd4) ? AGES4 : (ways == 3'd2) ? AGES2 : '0;
        end else if (en && look_valid[p]) begin
          for (int w = 0; w < MAX_WAYS; w++) begin
            if (3'(w) < ways) begin
              if (2'(w) == way) age[{base | EW'(w), 1'b0} +: AGW] <= '0;
              else if (age[{base | EW'(w), 1'b0} +: AGW] < way_age)
                age[{base | EW'(w), 1'b0} +: AGW] <= age[{base | EW'(w), 1'b0} +: AGW] + 1'b1;
            end
          end
          if (!found) begin
            tag[base | EW'(way)]   <= line;
            valid[base | EW'(way)] <= 1'b1;
          end
        end
      end
    end
  endgenerate
endmodule
