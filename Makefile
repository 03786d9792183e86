# Texture unit: golden model, RTL, SystemC. `make help` lists the targets.
BUILD ?= build
JOBS  ?= $(shell nproc)
OUT   ?= out
TEXSIM = $(BUILD)/texsim

.PHONY: help deps build demo test test-suites test-xprop unit-tests model-test model-alone formal-proofs bench bench-ir clean lint formal xprop synth synth-latch rtl-soak figures memory-report explore scenes hostile-models test-sanitize fuzz cluster-test

help:
	@echo "make demo   - build texsim only (not the tests), then render the default scene (writes $(OUT)/)"
	@echo "make test   - build, then run every test suite"
	@echo "make model-test - the golden model and its tests alone (no OpenImageIO, Verilator, SystemC)"
	@echo "make bench  - samples/s of the model, OpenImageIO TextureSystem, every engine and the RTL per configuration"
	@echo "make bench-ir - the RTL's instructions per clock per configuration, on RGBA8 and (the formats unit) BC1, BC7, sRGB, ETC2, EAC and ASTC textures (callgrind: independent of the machine's load)"
	@echo "make figures - the paper's experiments: comparisons, errors, flicker in $(OUT)/figures/index.html"
	@echo "make memory-report - cached memory through the RTL: throughput, hit rate, bytes, FIFO vs latency (docs/memory.md)"
	@echo "make scenes - real frames: the assimp test models through the cached RTL at latency 200: $(OUT)/scenes/index.html (SCENES_ENGINE=systemc: behind the TLM sockets)"
	@echo "make explore - sweep cache size, ways, block shape, latency, FIFO and pixel order over plane and panel, every point timed: $(OUT)/explore/index.html"
	@echo "make cluster-test - a real single-node Slurm on this machine (installs slurm-wlm and munge as root): a 240-point sweep as a job array, a failing task resubmitted, the merged CSV equal to a local one (docs/cluster.md)"
	@echo "make rtl-soak  - RTL vs model lockstep and the block decoders (1.2 M blocks), 20x the random samples of make test, new seeds"
	@echo "make test-sanitize - the model, sim and CLI suites built with AddressSanitizer and UBSan (build-sanitize/) and run"
	@echo "make fuzz   - every parser of untrusted bytes under libFuzzer, ASan and UBSan (clang, build-fuzz/), FUZZ_SECONDS each (default 30); findings kept in tests/fuzz/findings/ (make test replays them)"
	@echo "make hostile-models - every file of assimp-testmodels through texsim render: each renders or stops with one error line, within 1 GiB and 30 s"
	@echo "make lint   - verilator -Wall on rtl/ in several configurations (zero warnings)"
	@echo "make xprop  - 4-state X-propagation run of the RTL in Icarus Verilog, with planted bugs"
	@echo "make formal - Yosys proofs of the handshakes (skid buffer, req_ready path), the AXI4 read master and the AXI4-Lite slave, each shown failing on a planted bug (about 5 minutes on one core; make test runs the proofs only)"
	@echo "make synth  - every compiled configuration through Yosys for ECP5, Artix-7 and iCE40: LUTs, FFs, BRAM, DSP, parts it fits, nextpnr-ice40 Fmax ($(OUT)/synth/synth.json, about two hours)"
	@echo "make clean  - remove $(BUILD)/ and $(OUT)/"

# Installs missing Debian packages (as root), then configures once.
deps:
	@bash scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# The paper's receding plane (fig. 7): point sampling vs trilinear, both through the Verilated RTL
# (ideal timing, the default), each checked bit for bit against the golden model (--verify).
demo: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target texsim
	@mkdir -p $(OUT)
	$(TEXSIM) render --scene plane --texture checker --filter point --engine rtl --verify --out $(OUT)/plane_point.png
	$(TEXSIM) render --scene plane --texture checker --filter trilinear --engine rtl --verify --out $(OUT)/plane_trilinear.png
	$(TEXSIM) render --scene plane --texture checker --filter anisotropic --engine rtl --verify --out $(OUT)/plane_anisotropic.png
	$(TEXSIM) render --scene plane --texture testcard:1000x600 --filter trilinear --wrap mirror --engine rtl --verify --out $(OUT)/plane_1000x600_mirror.png
	@echo "demo: $(OUT)/plane_point.png aliases near the horizon, $(OUT)/plane_trilinear.png blurs it grey," \
	      "$(OUT)/plane_anisotropic.png keeps its checks; $(OUT)/plane_1000x600_mirror.png: a texture of no power-of-two size"

# Two at a time: the formal proofs (one core, about a minute; they need no build; their planted bugs
# are make formal's) start at once beside the build, then lint, xprop, synth-latch, the model
# library alone and ctest (whose own jobs share the other core until the proofs are done). Lines
# of the streams interleave whole (--output-sync=line).
test: deps $(BUILD)/CMakeCache.txt
	@$(MAKE) --no-print-directory --output-sync=line -j 2 test-suites

test-suites: formal-proofs build lint synth-latch model-alone unit-tests test-xprop

# (In make test: after the whole build, never a second cmake build beside it in the same tree.)
# (Its planted bugs, which show that the bench can fail, are make xprop's.)
test-xprop: build
	@XPROP_MUTANTS=0 bash scripts/xprop.sh $(BUILD)

unit-tests: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The model without any simulator or image library: its own build tree.
model-test: deps
	cmake -S . -B $(BUILD)-model -DCMAKE_BUILD_TYPE=Release -DTEXUNIT_MODEL_ONLY=ON > /dev/null
	cmake --build $(BUILD)-model -j $(JOBS)
	cd $(BUILD)-model && ctest --output-on-failure -j $(JOBS)

# In make test: the model-only tree configures (it looks for no OpenImageIO, Verilator or SystemC).
# The model's tests run in the main tree, where texunit_model_tests links the model and GoogleTest
# only, and the model compiles with the same flags.
model-alone: deps
	cmake -S . -B $(BUILD)-model -DCMAKE_BUILD_TYPE=Release -DTEXUNIT_MODEL_ONLY=ON > /dev/null

bench: build
	cmake --build $(BUILD) -j $(JOBS) --target texunit_bench
	$(BUILD)/texunit_bench

# The Verilated RTL's instructions per clock under callgrind (machine-independent; about 2 minutes).
bench-ir: build
	scripts/rtl_instructions.sh $(BUILD) $(OUT)/bench-ir

# The cached memory hierarchy through the RTL: the tables and plot of docs/memory.md §5 (about 3 minutes).
memory-report: build
	/usr/bin/python3 scripts/memory_report.py --texsim $(TEXSIM) --out $(OUT)/memory

# Real frames (docs/scenes.md): the assimp test models through the cached RTL, latency 200, verified
# against the model; frames, contact sheet and table in $(OUT)/scenes/ (about a minute).
# SCENES_ENGINE=systemc: the same RTL behind the SystemC/TLM-2.0 sockets.
SCENES_ENGINE ?= rtl
scenes: build
	/usr/bin/python3 scripts/scenes_report.py --texsim $(TEXSIM) --out $(OUT)/scenes --engine $(SCENES_ENGINE)

# The default architecture sweep (docs/memory.md §6): plane and panel, 640x480, the 1024x1024 test
# card, scanline and tiled order, caches 1..64 KiB of 1, 2 and 4 ways, blocks 4x4, 2x2 and 8x8,
# latencies 50..800 clocks, 16 B/clock, FIFOs of 256 and 2048 samples, every point timed by the
# model's timing layer (most of these have no Verilated build); tasks in $(JOBS) processes, the
# points already in the results store (~/.cache/texsim/results) reused.
explore: build
	$(TEXSIM) explore --scene plane,panel --cache-kib 1,2,4,8,16,32,64 --ways 1,2,4 --block 4x4,2x2,8x8 --format rgba8,bc1,bc7 \
	  --mem-latency 50,100,200,400,800 --fifo-depth 256,max --jobs $(JOBS) --out $(OUT)/explore

# texsim explore through a throw-away Slurm (scripts/cluster_test.sh; docs/cluster.md): about a minute.
cluster-test: build
	bash scripts/cluster_test.sh $(BUILD)

# The paper's scenes through an engine (FIG_ENGINE, default model) vs a real-valued reference (docs/scenes.md).
FIG_ENGINE ?= model
figures: build
	$(TEXSIM) figures --engine $(FIG_ENGINE) --width 320 --height 240 --reference-samples 6 --out $(OUT)/figures
	$(TEXSIM) mip --texture testcard:256x256 --layout $(OUT)/figures/fig1_layout.png
	/usr/bin/python3 scripts/figures.py $(OUT)/figures

# Long RTL soak (docs/verification.md): a failing case prints TEX_SEED; replay with the same base.
ifndef RTL_SOAK_SEED
RTL_SOAK_SEED := $(shell date +%s)
endif
rtl-soak: build
	@echo "rtl-soak: TEX_SEED_BASE=$(RTL_SOAK_SEED)"
	cd $(BUILD) && TEX_SCALE=20 TEX_SEED_BASE=$(RTL_SOAK_SEED) ./tests/rtl/texunit_rtl_tests --gtest_filter='RtlRandom.*:RtlBlockDecode.*'

# The model, sim and CLI suites with ASan + UBSan, in a tree of their own (docs/verification.md).
SAN_BUILD ?= build-sanitize
test-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -DTEXUNIT_SANITIZE=ON
	cmake --build $(SAN_BUILD) -j $(JOBS) --target texunit_model_tests texunit_sim_tests texunit_reference_tests texsim fuzz_replays
	cd $(SAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitize/lsan.supp:print_suppressions=0 \
	  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions=$(CURDIR)/tests/sanitize/ubsan.supp \
	  ctest -j $(JOBS) -L 'model|sim' -E '$(SAN_EXCLUDE)' --output-on-failure
# Not run here (they run in make test): SampleStreamsInConstantMemory bounds texsim's resident
# memory, which ASan's shadow and quarantine inflate; MaxMemoryValuesAreChecked runs texsim under
# a data limit, which a build with ASan does not set (its shadow memory would count).
SAN_EXCLUDE = SampleStreamsInConstantMemory|MaxMemoryValuesAreChecked

# The fuzz targets (tests/fuzz/README.md) with clang's libFuzzer in a tree of their own.
FUZZ_BUILD ?= build-fuzz
fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DTEXUNIT_FUZZ=ON > /dev/null
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_targets
	@bash scripts/fuzz.sh $(FUZZ_BUILD) $(OUT)/fuzz

# Every file of Debian's assimp-testmodels through texsim render (scripts/hostile_models.py).
hostile-models: build
	@/usr/bin/python3 scripts/hostile_models.py --texsim $(TEXSIM)

lint:
	@bash scripts/lint.sh

formal: deps
	@bash scripts/formal.sh

# In make test: the proofs without the planted bugs (which show the checks can fail: make formal).
formal-proofs: deps
	@bash scripts/formal.sh --proofs

xprop: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) --target xprop_vectors -j $(JOBS)
	@bash scripts/xprop.sh $(BUILD)

# Yosys: a small tex_unit after proc, tex_lambda and tex_axil_config synthesized; fails on any latch (make test).
synth-latch:
	@bash scripts/synth.sh latch $(BUILD)

synth:
	@bash scripts/synth.sh $(BUILD) $(OUT)

clean:
	rm -rf $(BUILD) $(BUILD)-model $(OUT)
