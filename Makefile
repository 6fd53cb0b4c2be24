# The two commands of the README: `make run` and `make test`. Both install missing Debian
# packages first (scripts/setup.sh), so they work on a fresh Debian 12 machine as root.
JOBS ?= $(shell nproc)
RELEASE := build/release
TESTBUILD := build/test
OUT ?= out

BASELINE := benchmarks/reference_results/default
RULES := benchmarks/reference_results/rules.json
# Overrides that keep the gate fast under ASan: laser/real_logs on the first 50 relations of each
# log, no relations drawn, no per-relation values; calibration/real_logs on Censi's lstraight and
# l90, aces and MRCLAM robot 2; diagnosis/real_logs on aces and intel; sim_to_real on aces and
# robot 2, 120 s each (what each saves: docs/decisions.md). The baseline is made with the same file.
GATE_CONFIG := benchmarks/reference_results/gate_config.json
# Monte-Carlo runs per experiment in the gate (the baseline is made with the same number).
GATE_RUNS ?= 3

# Unity builds (CMake batches 8 sources of a target into one unit): the headers' inline code
# (Eigen, nlohmann-json, fmt, gtest) is generated once per batch instead of once per file, a
# half to a quarter of the compile CPU (docs/decisions.md). UNITY= (empty) builds file by file.
UNITY ?= -DCMAKE_UNITY_BUILD=ON

.PHONY: all setup build run test gate baseline bench bench-gate speed-baseline format clean

# Ninja, not Unix Makefiles: it keeps both cores busy across targets (the Release CLI build 140 →
# 128 s on 2 cores; docs/decisions.md). A build folder another generator made is configured
# afresh (CMake refuses to switch generators in place).
CMAKE_GENERATOR ?= Ninja
configure = { [ ! -f $(1)/CMakeCache.txt ] || grep -qx 'CMAKE_GENERATOR:INTERNAL=$(CMAKE_GENERATOR)' $(1)/CMakeCache.txt || rm -rf $(1); } && \
  cmake -S . -B $(1) -G "$(CMAKE_GENERATOR)"

all: build

# The apt time is printed on its own: the goals for `make run` and `make test` exclude it.
setup:
	@s=$$(date +%s); ./scripts/setup.sh; rc=$$?; \
	  echo "make: setup (Debian packages) took $$(( $$(date +%s) - s )) s"; exit $$rc

# Release build of the CLI (no tests) with g++ (clang needs more compile CPU), unity batches of 32
# sources (each library is then one unit: a shorter build than 16 or 8), -O1 rather than CMake's
# -O3: a shorter build and a faster suite with identical results (no fast-math; IEEE arithmetic is the same at any level). One precompiled
# header of Eigen, nlohmann-json, fmt and the standard library for every target (LOCBENCH_PCH). Eigen's
# decompositions are instantiated once (core/linear_algebra.h, core/compass_ekf_model.cpp) instead
# of in every unit using them. Measurements: docs/decisions.md.
build: setup
	@s=$$(date +%s); $(call configure,$(RELEASE)) -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
	  -DLOCBENCH_BUILD_TESTS=OFF -DLOCBENCH_PCH=ON $(UNITY) $(if $(UNITY),-DCMAKE_UNITY_BUILD_BATCH_SIZE=32) >/dev/null && cmake --build $(RELEASE) -j$(JOBS) --target locbench; rc=$$?; \
	  echo "make: build took $$(( $$(date +%s) - s )) s"; exit $$rc

# Default suite on embedded defaults → JSON reports under $(OUT)/, a summary table, and the page
# a person reads, $(OUT)/report.html (tables and gnuplot charts, self-contained). Monte-Carlo
# runs use every core (THREADS, default all; results are the same for any number).
# The whole default suite, every real log at full length (the trim it once had is gone since the
# diagnosis got faster: docs/decisions.md). `make run RUN_CONFIG=FILE` runs it with a config's
# overrides (`locbench run --config`).
THREADS ?= $(shell nproc)
RUN_CONFIG ?=
run: build
	@s=$$(date +%s); $(RELEASE)/cli/locbench run --out $(OUT) --threads $(THREADS) $(if $(RUN_CONFIG),--config $(RUN_CONFIG)); rc=$$?; \
	  echo "make: suite took $$(( $$(date +%s) - s )) s"; exit $$rc
	@s=$$(date +%s); $(RELEASE)/cli/locbench report $(OUT) -o $(OUT)/report.html; rc=$$?; \
	  echo "make: report took $$(( $$(date +%s) - s )) s"; exit $$rc

# Debug + AddressSanitizer + UndefinedBehaviorSanitizer, warnings as errors, every test via CTest,
# then the default suite gated against the committed baseline. -g1 (line tables: sanitizer reports
# keep file:line) instead of -g: faster compiles, smaller objects, faster links. No precompiled
# headers: the cost is code generation under ASan, not parsing. The numerical libraries are
# compiled at -O1 (LOCBENCH_OPTIMIZE_NUMERICS) and without the sanitizers (LOCBENCH_SANITIZE_NUMERICS=OFF;
# they keep libstdc++'s and Eigen's bounds assertions): the sanitizers stay on every reader, the
# reports, the CLI and the tests. `make test SANITIZE_NUMERICS=ON` instruments everything.
# Measurements: docs/decisions.md.
SANITIZE_NUMERICS ?= OFF
test: setup
	@$(call configure,$(TESTBUILD)) -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-g1 -DLOCBENCH_SANITIZE=ON \
	  -DLOCBENCH_WERROR=ON -DLOCBENCH_OPTIMIZE_NUMERICS=ON \
	  -DLOCBENCH_SANITIZE_NUMERICS=$(SANITIZE_NUMERICS) $(UNITY) >/dev/null
	@s=$$(date +%s); cmake --build $(TESTBUILD) -j$(JOBS) && echo "make test: build took $$(( $$(date +%s) - s )) s"
	@s=$$(date +%s); cd $(TESTBUILD) && ctest --output-on-failure -j$(JOBS); rc=$$?; \
	  echo "make test: ctest took $$(( $$(date +%s) - s )) s"; exit $$rc
	@s=$$(date +%s); $(MAKE) --no-print-directory gate LOCBENCH=$(TESTBUILD)/cli/locbench; rc=$$?; \
	  echo "make test: gate took $$(( $$(date +%s) - s )) s"; exit $$rc

# Run the default suite and compare it with the baseline (exit 1 on a regression).
LOCBENCH ?= $(RELEASE)/cli/locbench
GATE_OUT := build/gate
gate:
	@rm -rf $(GATE_OUT) && mkdir -p $(GATE_OUT)
	$(LOCBENCH) run --runs $(GATE_RUNS) --config $(GATE_CONFIG) --out $(GATE_OUT)/reports > $(GATE_OUT)/summary.txt
	$(LOCBENCH) gate $(GATE_OUT)/reports --baseline $(BASELINE) --rules $(RULES) \
	  --markdown $(GATE_OUT)/gate.md --json $(GATE_OUT)/gate.json

# Refresh the committed baseline deliberately (review the diff, then commit it).
baseline: build
	@rm -rf $(BASELINE)
	$(RELEASE)/cli/locbench run --runs $(GATE_RUNS) --config $(GATE_CONFIG) --out $(BASELINE)

# Google Benchmark kernels (Release, CMake's -O3), JSON in $(OUT)/speed.json.
BENCHBUILD := build/bench
bench: setup
	@$(call configure,$(BENCHBUILD)) -DCMAKE_BUILD_TYPE=Release -DLOCBENCH_BUILD_TESTS=OFF >/dev/null
	@cmake --build $(BENCHBUILD) -j$(JOBS) --target locbench_speed
	@mkdir -p $(OUT)
	$(BENCHBUILD)/benchmarks/speed/locbench_speed --benchmark_out=$(OUT)/speed.json --benchmark_out_format=json

# The matcher kernels (181 beams, 5 repetitions) gated by same-run speed ratios against the
# committed benchmarks/reference_results/speed/kernels.json (rules: speed_rules.json beside it).
SPEED_BASELINE := benchmarks/reference_results/speed/kernels.json
SPEED_RULES := benchmarks/reference_results/speed_rules.json
# The 181-beam kernels and EAP / split-and-merge on the first 200 ACES and Intel scans, the scan-pair
# correctors per Intel scan, the whole Intel replay through EAP + iterated solve, and the
# diagnosis of one real log per kind (Intel: relations; MRCLAM robot 1: TRUEPOS) and of a
# synthetic one (the real-log kernels are skipped without the data), 5 repetitions interleaved at
# random so that load drifts hit every kernel.
SPEED_ARGS := --benchmark_filter='Match.*/181/|RealScans/(aces|intel)/(eap|split_and_merge)|Correct/(eap_ch6_ls|eap_iterated_pl|pl_icp)/intel|IntelReplay/eap_iterated_pl|Diagnose/(intel_relations|mrclam6_robot1_truepos)|DiagnoseHiddenEffects' \
  --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true --benchmark_min_time=0.05
bench-gate: build
	@$(call configure,$(BENCHBUILD)) -DCMAKE_BUILD_TYPE=Release -DLOCBENCH_BUILD_TESTS=OFF >/dev/null
	@cmake --build $(BENCHBUILD) -j$(JOBS) --target locbench_speed
	@mkdir -p $(OUT)
	$(BENCHBUILD)/benchmarks/speed/locbench_speed $(SPEED_ARGS) --benchmark_out=$(OUT)/speed_kernels.json --benchmark_out_format=json
	$(RELEASE)/cli/locbench gate $(OUT)/speed_kernels.json --baseline $(SPEED_BASELINE) --rules $(SPEED_RULES)

# Refresh the speed baseline deliberately (same machine class as the gate; review, commit).
speed-baseline: setup
	@$(call configure,$(BENCHBUILD)) -DCMAKE_BUILD_TYPE=Release -DLOCBENCH_BUILD_TESTS=OFF >/dev/null
	@cmake --build $(BENCHBUILD) -j$(JOBS) --target locbench_speed
	$(BENCHBUILD)/benchmarks/speed/locbench_speed $(SPEED_ARGS) --benchmark_out=$(SPEED_BASELINE) --benchmark_out_format=json

# Rewrites the C++ sources as clang-format writes them (.clang-format); the test
# Style.EverySourceIsClangFormatted fails on any file that differs.
format: setup
	git ls-files '*.cpp' '*.h' ':!tests/style/misformatted' | xargs clang-format -i

clean:
	rm -rf build $(OUT)

# libFuzzer targets (fuzz/: one per reader, the scenario through the simulator and the CARMEN
# writer, Censi tuples through the ML calibration, the JSON-option layer), built with clang
# (Debian clang-14 + libclang-rt-14-dev, from scripts/setup.sh) under ASan/UBSan into
# build/fuzz, then each run for FUZZ_SECONDS from its seed corpus (fuzz/corpus/, plus the first
# lines of the real logs). A finding fails and leaves its input in build/fuzz/fuzz/ (crash-*,
# timeout-*, oom-*). `make run` and `make test` never use clang.
FUZZBUILD := build/fuzz
FUZZ_SECONDS ?= 30
FUZZ_TARGETS := fuzz_carmen fuzz_relations fuzz_tum fuzz_bags fuzz_landmarks fuzz_censi fuzz_umbmark_input fuzz_scenario \
  fuzz_histogram fuzz_reports fuzz_json_options
.PHONY: fuzz
fuzz: setup
	@$(call configure,$(FUZZBUILD)) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Release \
	  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -g1" -DLOCBENCH_FUZZ=ON -DLOCBENCH_FUZZ_SECONDS=$(FUZZ_SECONDS) $(UNITY) >/dev/null
	@s=$$(date +%s); cmake --build $(FUZZBUILD) -j$(JOBS) --target $(FUZZ_TARGETS) && \
	  echo "make fuzz: build took $$(( $$(date +%s) - s )) s"
	@s=$$(date +%s); cd $(FUZZBUILD) && ctest -L fuzz --output-on-failure -j$(JOBS); rc=$$?; \
	  echo "make fuzz: $(words $(FUZZ_TARGETS)) targets, $(FUZZ_SECONDS) s each, took $$(( $$(date +%s) - s )) s"; exit $$rc
