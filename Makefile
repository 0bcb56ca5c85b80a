# The two commands a new user types: `make run` and `make test` (see README.md).
BUILD_DIR   ?= build
BUILD_TYPE  ?= Release
JOBS        ?= $(shell nproc)
FUZZ_SECONDS ?= 60
# CI (CI=true) turns warnings into errors.
WERROR      := $(if $(CI),ON,OFF)

.PHONY: all deps configure build run test unit fuzz format clean

all: build

deps:
	@scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DCLOTH_WERROR=$(WERROR) >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j$(JOBS)

# The main job: simulate the drape scene headless and write its final frame.
run: build
	@mkdir -p out
	$(BUILD_DIR)/clothsim run scenes/drape.json --out-obj out/drape.obj --out-csv out/drape.csv
	@echo "result: out/drape.obj (Wavefront OBJ, opens in Blender) and out/drape.csv"

# The whole suite: the scene-loader fuzzer, then every GoogleTest (CPU, GPU on EGL, CLI) via ctest.
test: fuzz unit

unit: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

fuzz: deps
	scripts/fuzz.sh $(FUZZ_SECONDS)

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD_DIR) build-fuzz out
