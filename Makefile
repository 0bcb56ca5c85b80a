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

# The main job: the drape scene in the viewer where there is a display; without one (or when no
# window can be opened), simulated headless, its final frame written as a picture, OBJ and CSV.
run: build
	@mkdir -p out
	@status=4; \
	if [ -n "$$DISPLAY$$WAYLAND_DISPLAY" ]; then \
	    $(BUILD_DIR)/clothsim view scenes/drape.json; status=$$?; \
	else \
	    echo "no display (DISPLAY and WAYLAND_DISPLAY are unset): rendering headless"; \
	fi; \
	if [ $$status -eq 4 ]; then \
	    $(BUILD_DIR)/clothsim render scenes/drape.json --png out/drape.png && \
	    $(BUILD_DIR)/clothsim run scenes/drape.json --out-obj out/drape.obj --out-csv out/drape.csv && \
	    echo "result: out/drape.png (picture), out/drape.obj (Wavefront OBJ, opens in Blender), out/drape.csv"; \
	else exit $$status; fi

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
