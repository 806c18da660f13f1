# uavslam: the two set-up commands are `make demo` and `make test`; each installs what is missing
# (docker/install-deps.sh, the one dependency list), configures and builds first.
BUILD      ?= build
BUILD_ASAN ?= build-asan
JOBS       ?= $(shell nproc)
UAVSLAM    := $(BUILD)/components/uavslam/uavslam

.PHONY: all deps configure build demo test test-unit test-asan bench sweep format format-check clean

all: build

deps:
	bash docker/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD) -j$(JOBS)

# The main job: the default flight simulated and mapped in-process, with its summary.
demo: build
	$(UAVSLAM) simulate --scenario config/scenarios/demo.yaml --config config/slam.yaml --out out/demo

# Every test: unit and integration tests of the release build, then the unit tests under
# AddressSanitizer + UndefinedBehaviorSanitizer.
test: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)
	$(MAKE) test-asan

test-asan: deps
	cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUAVSLAM_SANITIZE=ON
	cmake --build $(BUILD_ASAN) -j$(JOBS)
	cd $(BUILD_ASAN) && ctest -L unit --output-on-failure -j$(JOBS)

# Speed: the matcher benchmark's tables (README "Speed").
bench: build
	bash test/bench/matcher_table.sh --build-dir $(BUILD)

# Accuracy and time against ICP iterations and FLANN checks (README "Choosing the iteration count").
sweep: build
	$(UAVSLAM) sweep --scenario config/scenarios/demo.yaml --config config/slam.yaml \
	  --iterations 1,2,3,5,10,20 --checks exact,16,64

format:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

format-check:
	git ls-files '*.cpp' '*.hpp' | xargs clang-format --dry-run --Werror

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) out
