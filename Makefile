# Thin wrapper: `make run` and `make test` install what is missing, build, and run.
BUILD ?= build
JOBS ?= 2

.PHONY: all deps configure build run test bench install deb fuzz check-sanitize clean

all: build

deps:
	@scripts/install_deps.sh
	@scripts/fetch_paraview_python.sh $(BUILD)/paraview-python

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

run: build
	@scripts/main_job.sh $(BUILD)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@$(BUILD)/tests/kerf_benchmarks

# The command, libraries, headers, scenes and CMake package under PREFIX
# (find_package(kerf) with CMAKE_PREFIX_PATH=PREFIX), and the .deb of the
# same install (in $(BUILD); `apt install ./kerf_*.deb`).
PREFIX ?= /usr/local
install: build
	@cmake --install $(BUILD) --prefix $(PREFIX)

deb: build
	@cd $(BUILD) && cpack -G DEB

# Slow checks, not part of `make test`: libFuzzer on the scene and mesh
# readers (FUZZ_SECONDS each, default 600; clang-16, in build-fuzz), and the
# unit, regression and malformed tests under ASan + UBSan (build-sanitize).
FUZZ_SECONDS ?= 600
fuzz:
	@scripts/fuzz.sh $(FUZZ_SECONDS)

check-sanitize:
	@scripts/check_sanitize.sh

clean:
	rm -rf $(BUILD) build-sanitize build-fuzz
