# uavslam: the two set-up commands are `make demo` and `make test`; each installs what is missing
# (docker/install-deps.sh, the one dependency list), configures and builds first.
BUILD      ?= build
BUILD_ASAN ?= build-asan
JOBS       ?= $(shell nproc)
# ccache keys on paths relative to the checkout, so a fresh clone (CI) reuses earlier builds.
export CCACHE_BASEDIR := $(CURDIR)
UAVSLAM    := $(BUILD)/bin/uavslam

.PHONY: all deps configure build demo simulate test test-unit test-asan bench bench-latency sweep real-logs \
        format format-check clean

all: build

deps:
	bash docker/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD) -j$(JOBS)

# The main job: the six DDS processes (config/launch/demo.yaml) fly 90 s of the demo scenario in
# real time on loopback, then the run's summary (out/demo).
demo: build
	rm -rf out/demo
	$(UAVSLAM) launch config/launch/demo.yaml
	$(UAVSLAM) report out/demo

# The whole 180 s demo flight mapped in-process (no DDS), as fast as the pipeline goes.
simulate: build
	$(UAVSLAM) simulate --scenario config/scenarios/demo.yaml --config config/slam.yaml \
	  --out out/simulate

# Every test: unit and integration tests of the release build, then the unit tests under
# AddressSanitizer + UndefinedBehaviorSanitizer.
test: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)
	$(MAKE) test-asan

test-asan: deps
	cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUAVSLAM_SANITIZE=ON
	cmake --build $(BUILD_ASAN) -j$(JOBS) --target unit_tests
	cd $(BUILD_ASAN) && ctest -L unit --output-on-failure -j$(JOBS)

# Speed: the matcher benchmark's tables and the end-to-end latency (README "Speed").
bench: build
	bash test/bench/matcher_table.sh --build-dir $(BUILD)
	$(MAKE) bench-latency

# Scan publish -> pose received through a real slam_matcher process, 40 Hz, 60 s of the demo flight,
# with the normal scheduler and with SCHED_FIFO (as on the vehicle; needs root).
bench-latency: build
	$(BUILD)/test/bench/bench_latency --scenario config/scenarios/demo.yaml --duration 60
	$(BUILD)/test/bench/bench_latency --scenario config/scenarios/demo.yaml --duration 60 \
	  --realtime-priority 50

# Accuracy and time against ICP iterations and FLANN checks (README "Choosing the iteration count").
sweep: build
	$(UAVSLAM) sweep --scenario config/scenarios/demo.yaml --config config/slam.yaml \
	  --iterations 1,2,3,5,10,20 --checks exact,16,64

# The Freiburg benchmark table of README "Real logs" (needs ../shared/data/freiburg; ~5 min).
real-logs: build
	bash test/bench/real_logs_table.sh --build-dir $(BUILD)

format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

format-check:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format --dry-run --Werror

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) out
