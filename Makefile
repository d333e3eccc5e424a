# upkie-rl: the two-command quick start is `make train` and `make test`.
BUILD_DIR ?= build
SANITIZE_DIR ?= build-sanitize
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
PYTHON ?= python3

.PHONY: all deps configure build test test-cpp test-python bench train sanitize format tidy clean

all: build

deps:
	bash scripts/install-deps.sh

$(BUILD_DIR)/build.ninja:
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

configure: $(BUILD_DIR)/build.ninja

build: deps configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

test-cpp:
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

test-python:
	@if ls python/tests/test_*.py >/dev/null 2>&1; then \
	  UPKIE_RL_BUILD_DIR=$(abspath $(BUILD_DIR)) $(PYTHON) -m pytest -q python/tests; \
	else echo "no Python tests yet"; fi

test: build
	$(MAKE) test-cpp
	$(MAKE) test-python

bench: build
	for program in $(BUILD_DIR)/bench/*_bench; do $$program --benchmark_min_time=1; done

sanitize: deps
	cmake -S . -B $(SANITIZE_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUPKIE_RL_SANITIZE=ON -DUPKIE_RL_BUILD_BENCH=OFF
	cmake --build $(SANITIZE_DIR) -j $(JOBS)
	cd $(SANITIZE_DIR) && ctest --output-on-failure -j $(JOBS)

format:
	find src tests bench -name '*.hpp' -o -name '*.cpp' | xargs clang-format -i

tidy: configure
	find src -name '*.cpp' | xargs clang-tidy -p $(BUILD_DIR) --quiet

clean:
	rm -rf $(BUILD_DIR) $(SANITIZE_DIR)
