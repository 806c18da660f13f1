# uavslam: the two set-up commands are `make demo` and `make test`; each installs what is missing
# (docker/install-deps.sh, the one dependency list), configures and builds first.
BUILD      ?= build
BUILD_ASAN ?= build-asan
BUILD_FUZZ ?= build-fuzz
FUZZ_SECONDS ?= 30
JOBS       ?= $(shell nproc)
# ccache keys on paths relative to the checkout, so a fresh clone (CI) reuses earlier builds.
export CCACHE_BASEDIR := $(CURDIR)
UAVSLAM    := $(BUILD)/bin/uavslam

.PHONY: all deps configure build programs demo simulate offline test test-unit test-asan fuzz bench bench-latency bench-link sweep real-logs \
        format format-check clean

all: build

deps:
	bash docker/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD) -j$(JOBS)

# The six processes and the uavslam tool, without the tests: what demo, simulate and offline run.
programs: configure
	cmake --build $(BUILD) -j$(JOBS) --target programs

# The main job: the six DDS processes (config/launch/demo.yaml) fly 90 s of the demo scenario in
# real time on loopback, then the run's summary (out/demo).
demo: programs
	rm -rf out/demo
	$(UAVSLAM) launch config/launch/demo.yaml
	$(UAVSLAM) report out/demo

# The whole 180 s demo flight mapped in-process (no DDS), as fast as the pipeline goes.
simulate: programs
	$(UAVSLAM) simulate --scenario config/scenarios/demo.yaml --config config/slam.yaml \
	  --out out/simulate

# The offline dense mapper on the demo flight's log (written by simulate --log), with the real-time
# pass over the same log for comparison (docs/recordings.md "Offline dense mapping").
offline: programs
	$(UAVSLAM) simulate --quiet --scenario config/scenarios/demo.yaml --config config/slam.yaml \
	  --out out/simulate --log out/demo_flight.mcap
	$(UAVSLAM) offline --log out/demo_flight.mcap --sensor config/scenarios/demo.yaml \
	  --config config/slam.yaml --out out/offline

# Every test: unit and integration tests of the release build, then the unit tests under
# AddressSanitizer + UndefinedBehaviorSanitizer, then the log readers fuzzed for a bounded time.
test: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)
	$(MAKE) test-asan
	$(MAKE) fuzz

test-asan: deps
	cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUAVSLAM_SANITIZE=ON
	cmake --build $(BUILD_ASAN) -j$(JOBS) --target unit_tests
	cd $(BUILD_ASAN) && ctest -L unit --output-on-failure -j$(JOBS)

# The CARMEN, MCAP, SCIP 2.0 and MAVLink readers under libFuzzer (clang, with ASan and UBSan), FUZZ_SECONDS each:
# seeds from test/fuzz/corpus, the inputs it finds kept in $(BUILD_FUZZ)/corpus for the next run;
# a crash leaves its input as crash-* here and fails the target.
fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(BUILD_FUZZ) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DUAVSLAM_FUZZ=ON -DUAVSLAM_BENCH=OFF
	cmake --build $(BUILD_FUZZ) -j$(JOBS) --target fuzz_targets
	for reader in carmen mcap scip2 mavlink; do \
	  mkdir -p $(BUILD_FUZZ)/corpus/$$reader && \
	  log=$(BUILD_FUZZ)/fuzz_$$reader.log; \
	  if ! $(BUILD_FUZZ)/test/fuzz/fuzz_$${reader}_reader -max_total_time=$(FUZZ_SECONDS) \
	      -rss_limit_mb=2048 -malloc_limit_mb=512 -max_len=16384 -print_final_stats=1 \
	      $(BUILD_FUZZ)/corpus/$$reader test/fuzz/corpus/$$reader > $$log 2>&1; then \
	    tail -60 $$log; echo "fuzz: fuzz_$${reader}_reader failed (whole output: $$log)"; exit 1; \
	  fi; \
	  echo "fuzz: fuzz_$${reader}_reader: $$(grep -h '^Done' $$log), no crash"; \
	done

# Speed: the matcher benchmark's tables and the end-to-end latency (docs/speed.md).
bench: build
	bash test/bench/matcher_table.sh --build-dir $(BUILD)
	$(MAKE) bench-latency

# Scan publish -> pose received through a real slam_matcher process, 40 Hz, 60 s of the demo flight,
# with the normal scheduler and with SCHED_FIFO (as on the vehicle; needs root).
bench-latency: build
	$(BUILD)/test/bench/bench_latency --scenario config/scenarios/demo.yaml --duration 60
	$(BUILD)/test/bench/bench_latency --scenario config/scenarios/demo.yaml --duration 60 \
	  --realtime-priority 50

# The system across an emulated WiFi link between two network namespaces (needs root;
# docs/deployment.md "Two hosts over WiFi"): loopback reference, matcher on board, matcher on the ground, an outage.
bench-link: build
	$(BUILD)/test/net/bench_link --scenario config/scenarios/demo.yaml --duration 60 \
	  --outage-at 30 --out out/bench_link

# Accuracy and time against ICP iterations and FLANN checks (docs/algorithm.md "Choosing the iteration count").
sweep: programs
	$(UAVSLAM) sweep --scenario config/scenarios/demo.yaml --config config/slam.yaml \
	  --iterations 1,2,3,5,10,20 --checks exact,16,64

# The Freiburg benchmark table of docs/real-logs.md (needs ../shared/data/freiburg; ~15 min).
real-logs: programs
	bash test/bench/real_logs_table.sh --build-dir $(BUILD)

format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

format-check:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format --dry-run --Werror

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD_FUZZ) out
