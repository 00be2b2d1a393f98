# modelc: every entry point. `make help` lists them.
#
#   make deps                    install the Debian packages that are missing (apt-get, sudo when not root)
#   make deps-bench              install the benchmarks' big extras (BENCH_PACKAGES: libvisp-dev, ~200 packages)
#   make demo                    deps + generator + bake the default model + its viewer + a PNG and stats
#   make test                    the whole test suite, two suites at a time; last line "N passed, N failed, N skipped"
#   make view MODEL=file [NAME=n] [DEPTH=d]   bake any model file and build build/NAME/NAME-view
#   make web MODEL=file [NAME=n] [WEB_SIZE=WxH] [WEB_STREAM=1]  bake it and build build/NAME/web/: index.html + NAME.wasm (no libc), open it in a browser;
#                                WEB_STREAM=1: also stream.html, which fetches the bake's stream NAME.mcs level by level (serve the folder over http)
#   make track MODEL=file [NAME=n]           bake an edge model (.cao or mesh) and build build/NAME/NAME-track
#   make models                  extract the catalogue's sample models under build/models/
#   make bench                   benchmarks, written to tests/bench/RESULTS.md
#   make bench-accuracy          run time against error: depth, fraction bits, float (about 12 min)
#   make bench-pmesh             progressive-mesh level changes and flash per split against OpenMesh
#   make bench-mesh              filled triangles and line drawings against Mesa llvmpipe on one thread
#   make bench-silhouette        silhouette search: recall against work, against the exact scan
#   make bench-track             the tracker: time and error on synthetic and ViSP's real cube sequences, beside ViSP (make deps-bench); the line walk's two forms
#   make bench-lod-auto          the automatic level of detail against frame-time targets
#   make bench-neighbours        line drawings at coarse levels with and without the neighbour table
#   make bench-cones             face groups' normal cones, line pixels near the faces: what a hierarchy could spare the line drawings
#   make bench-lod-error         level of detail: error (PSNR, coverage) against run time, shaded frames
#   make bench-views             the point renderer at every view (zoom, size, perspective, deeper bakes), level of detail on and off, beside Mesa
#   make bench-web               the web viewer's module in headless Chromium beside the native viewer, side by side
#   make stress                  10^7 random views against the double-precision reference (about 13 min), freestanding -O0..-O3,-Os
#   make fuzz                    the ASan + UBSan generator, then libFuzzer on each reader and the bake, FUZZ_SECONDS=600 each

SHELL := /bin/bash
# Debian's programs first: make deps installs them, and the build, tests and benchmarks run them by
# name. python3 above all: the suites start it hundreds of times, and a python3 found earlier on PATH
# (a pyenv build whose modules were never compiled, say) took 0.57 s of CPU a start here against
# 0.05 s for Debian's.
export PATH := /usr/bin:/bin:$(PATH)
.DEFAULT_GOAL := help
include models/catalogue.mk

BUILD := build
CC ?= cc
CXX ?= g++
CFLAGS ?= -O2 -g
CXXFLAGS ?= -O2 -g
RT_CFLAGS := -std=c99 -ffreestanding -Wall -Wextra -Werror -Iruntime/include
HOST_CFLAGS := -std=c99 -Wall -Wextra -Werror -Iruntime/include
GEN_CXXFLAGS := -std=c++17 -Wall -Wextra -Igen -Iruntime/include -DCGAL_DISABLE_GMP=1 -DCGAL_NO_GMP=1
# -ltinygltf: the glTF reader (gen/input/gltf.cpp); -lstb: its texture decoding (stb_image, which
# Debian's libtinygltf itself links)
GEN_LIBS := -lmstch -lOpenMeshTools -lOpenMeshCore -ltinygltf -lstb -lpthread

# Debian packages: the build, the tests and the benchmarks (libopenmesh-dev: the mesh part's
# progressive meshes and decimation; the readers in gen/input/ do not use it; libtinygltf-dev: the
# glTF reader; assimp-testmodels: the glTF samples tests/gen/gltf.sh bakes, 20 MB)
DEB_PACKAGES := build-essential clang lld chromium libopenmesh-dev libcgal-dev libcgal-demo libeigen3-dev libboost-dev \
  libcli11-dev nlohmann-json3-dev libmstch-dev libstb-dev libtinygltf-dev libcmocka-dev valgrind tmux gnuplot-nox \
  libclang-rt-14-dev \
  libosmesa6-dev draco netpbm python3 perl strace bsdutils coreutils \
  gcc-arm-none-eabi binutils-arm-none-eabi picolibc-arm-none-eabi qemu-system-arm \
  visp-images-data assimp-testmodels
# the benchmarks' big extras, not in every CI run: ViSP's tracker for tests/bench/visp_track.cpp (make deps-bench)
BENCH_PACKAGES := libvisp-dev
SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: help deps gen models views demo view web track readme-images test bench stress clean
help:
	@sed -n 's/^#   //p' Makefile

deps:
	@missing=$$(for p in $(DEB_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "installing:" $$missing; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing >/dev/null; \
	else echo "deps: all installed"; fi

.PHONY: deps-bench
deps-bench:
	@missing=$$(for p in $(BENCH_PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "installing:" $$missing; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing >/dev/null; \
	else echo "deps-bench: all installed"; fi

# ---- generator -------------------------------------------------------------------------------
# gen/*.cpp and one level of subfolders (gen/input/, ...); objects mirror the tree under build/gen/
GEN_SRC := $(wildcard gen/*.cpp gen/*/*.cpp)
GEN_HDR := $(wildcard gen/*.hpp gen/*/*.hpp)
GEN_OBJ := $(patsubst gen/%.cpp,$(BUILD)/gen/%.o,$(GEN_SRC)) $(BUILD)/gen/templates.o
TEMPLATES := $(wildcard templates/*.mustache)
MODELC := $(BUILD)/bin/modelc

gen: $(MODELC)
$(MODELC): $(GEN_OBJ)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) -o $@ $^ $(GEN_LIBS)
# -MMD: each object also depends on the runtime headers it includes (mesh_face.h's code, the layouts'
# macros), which GEN_HDR does not list
$(BUILD)/gen/%.o: gen/%.cpp $(GEN_HDR)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(GEN_CXXFLAGS) -MMD -MP -c -o $@ $<
-include $(GEN_OBJ:.o=.d)
# the templates are compiled into the generator, so build/bin/modelc runs from anywhere
$(BUILD)/gen/templates.cpp: $(TEMPLATES) Makefile
	@mkdir -p $(@D)
	@{ echo '#include "emit.hpp"'; echo '#include <map>'; echo '#include <stdexcept>'; \
	   echo 'const std::string &mc::template_text(const std::string &name) {'; \
	   echo '    static const std::map<std::string, std::string> t = {'; \
	   for f in $(TEMPLATES); do n=$$(basename $$f .mustache); \
	     printf '        {"%s", R"MCTPL(' "$$n"; cat $$f; echo ')MCTPL"},'; done; \
	   echo '    };'; echo '    auto it = t.find(name);'; \
	   echo '    if (it == t.end()) throw std::logic_error("no template " + name);'; \
	   echo '    return it->second;'; echo '}'; } > $@
$(BUILD)/gen/templates.o: $(BUILD)/gen/templates.cpp
	$(CXX) $(CXXFLAGS) $(GEN_CXXFLAGS) -c -o $@ $<

# ---- runtime ---------------------------------------------------------------------------------
RT_SRC := $(wildcard runtime/src/*.c)
RT_OBJ := $(patsubst runtime/src/%.c,$(BUILD)/runtime/%.o,$(RT_SRC))
RT_HDR := $(wildcard runtime/include/modelc/*.h runtime/src/*.h)
# front ends: host/ (viewer, terminal) and fw/ (firmware) each link common/ (view list, checksums, RGB)
COMMON_SRC := $(wildcard runtime/front/common/*.c)
COMMON_HDR := $(wildcard runtime/front/common/*.h)
HOST_SRC := $(wildcard runtime/front/host/*.c)
HOST_OBJ := $(patsubst runtime/front/host/%.c,$(BUILD)/host/%.o,$(HOST_SRC)) \
  $(patsubst runtime/front/common/%.c,$(BUILD)/common/%.o,$(COMMON_SRC))
# each function and object in its own section, so that a program's --gc-sections drops what it never calls
$(BUILD)/runtime/%.o: runtime/src/%.c $(RT_HDR)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(RT_CFLAGS) -ffunction-sections -fdata-sections -c -o $@ $<
$(BUILD)/host/%.o: runtime/front/host/%.c $(RT_HDR) $(wildcard runtime/front/host/*.h) $(COMMON_HDR)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(HOST_CFLAGS) -c -o $@ $<
$(BUILD)/common/%.o: runtime/front/common/%.c $(RT_HDR) $(COMMON_HDR)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(RT_CFLAGS) -c -o $@ $<
# the tracker front end: track/ with the host's PNG writer
TRACK_SRC := $(wildcard runtime/front/track/*.c)
TRACK_OBJ := $(patsubst runtime/front/track/%.c,$(BUILD)/track/%.o,$(TRACK_SRC)) $(BUILD)/host/image.o $(BUILD)/common/rgb.o \
  $(BUILD)/common/track_frame.o
$(BUILD)/track/%.o: runtime/front/track/%.c $(RT_HDR) $(wildcard runtime/front/track/*.h runtime/front/host/*.h) \
  runtime/front/common/track_frame.h
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $(HOST_CFLAGS) -c -o $@ $<
# the runtime and the host front end's objects alone: the tests link them (tests/lib.sh rt_objs)
# wherever they test the runtime as the viewers have it, instead of compiling it again
.PHONY: runtime-objs
runtime-objs: $(RT_OBJ) $(HOST_OBJ)

# ---- models, bakes and viewers -----------------------------------------------------------------
MODEL_FILES := $(foreach m,$(CATALOGUE),$(BUILD)/models/$(notdir $($(m).src)))
models: $(MODEL_FILES)
$(BUILD)/models/%:
	@test -f $(CGAL_DATA) || { echo "modelc: $(CGAL_DATA) missing: run make deps (package libcgal-demo)" >&2; exit 1; }
	@test -n "$(filter %/$*,$(foreach m,$(CATALOGUE),$($(m).src)))" || { echo "modelc: $@: no catalogue model has this file (models/catalogue.mk)" >&2; exit 1; }
	@mkdir -p $(@D)
	@tar -xzf $(CGAL_DATA) -O $(filter %/$*,$(foreach m,$(CATALOGUE),$($(m).src))) > $@.tmp && mv $@.tmp $@

# viewer: runtime + generated model + host front end; -ffunction-sections lets the linker drop
# runtime code the model does not use; --wrap makes any heap call an undefined reference
VIEW_LDFLAGS := -Wl,--gc-sections -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free -lm
link_view = $(CC) $(CFLAGS) $(RT_CFLAGS) -ffunction-sections -fdata-sections -o $(BUILD)/$(1)/$(1)-view \
  $(BUILD)/$(1)/*.c $(RT_OBJ) $(HOST_OBJ) $(VIEW_LDFLAGS)

link_track = $(CC) $(CFLAGS) $(RT_CFLAGS) -ffunction-sections -fdata-sections -o $(BUILD)/$(1)/$(1)-track \
  $(BUILD)/$(1)/*.c $(RT_OBJ) $(TRACK_OBJ) $(VIEW_LDFLAGS)

# build/NAME/budget.json stands for the whole bake of catalogue model NAME
define catalogue_rules
$(BUILD)/$(1)/budget.json: $(BUILD)/models/$(notdir $($(1).src)) $(MODELC)
	$(MODELC) $$< -o $(BUILD) --name $(1) $($(1).opts) $(BAKE_OPTS)
$(BUILD)/$(1)/$(1)-view: $(BUILD)/$(1)/budget.json $(RT_OBJ) $(HOST_OBJ)
	$$(call link_view,$(1))
endef
$(foreach m,$(CATALOGUE),$(eval $(call catalogue_rules,$(m))))
views: $(foreach m,$(CATALOGUE),$(BUILD)/$(m)/$(m)-view)

# make view MODEL=path/to/file [NAME=..] [DEPTH=..]
ifdef MODEL
NAME ?= $(shell basename "$(MODEL)" | sed 's/\.[^.]*$$//' | tr 'A-Z' 'a-z' | sed 's/[^a-z0-9_]/_/g; s/^[0-9]/m_&/')
DEPTH ?= 8
endif
view: $(MODELC) $(RT_OBJ) $(HOST_OBJ)
	@test -n "$(MODEL)" || { echo "usage: make view MODEL=path/to/file [NAME=name] [DEPTH=d]" >&2; exit 2; }
	$(MODELC) "$(MODEL)" -o $(BUILD) --name $(NAME) --depth $(DEPTH) $(BAKE_OPTS)
	$(call link_view,$(NAME))
	@echo "built $(BUILD)/$(NAME)/$(NAME)-view"

# make web MODEL=file [NAME=n] [DEPTH=d] [WEB_SIZE=WxH] [WEB_STREAM=1]: bake, then build/NAME/web/
# (index.html, viewer.js, NAME.wasm and its base64 twin for file://): runtime/front/web/build.sh;
# WEB_STREAM=1 bakes with --emit stream, and build.sh adds stream.html, NAME-stream.wasm and NAME.mcs
WEB_SRC := $(wildcard runtime/front/web/*) runtime/front/common/rgb.c runtime/front/common/mesh_frame.c $(RT_SRC) $(RT_HDR)
web: $(MODELC)
	@test -n "$(MODEL)" || { echo "usage: make web MODEL=path/to/file [NAME=name] [DEPTH=d] [WEB_SIZE=WxH] [WEB_STREAM=1]" >&2; exit 2; }
	$(MODELC) "$(MODEL)" -o $(BUILD) --name $(NAME) --depth $(DEPTH) $(BAKE_OPTS) $(if $(WEB_STREAM),--emit stream)
	runtime/front/web/build.sh $(BUILD) $(NAME) $(WEB_SIZE)
# a catalogue model's page from its bake
$(BUILD)/%/web/index.html: $(BUILD)/%/budget.json $(WEB_SRC)
	runtime/front/web/build.sh $(BUILD) $* $(WEB_SIZE)

# make track MODEL=file [NAME=n] [BAKE_OPTS=..]: bake an edge model (--as edges) and build build/NAME/NAME-track
track: $(MODELC) $(RT_OBJ) $(TRACK_OBJ)
	@test -n "$(MODEL)" || { echo "usage: make track MODEL=path/to/file.cao|mesh [NAME=name] [BAKE_OPTS=..]" >&2; exit 2; }
	$(MODELC) "$(MODEL)" -o $(BUILD) --name $(NAME) --as edges $(BAKE_OPTS)
	$(call link_track,$(NAME))
	@echo "built $(BUILD)/$(NAME)/$(NAME)-track"

# ViSP's cube (Debian visp-images-data): its model and camera sequence, the tracker's real data
VISP_MBT := /usr/share/visp-images-data/ViSP-images/mbt
$(BUILD)/cube/budget.json: $(MODELC)
	@test -f $(VISP_MBT)/cube.cao || { echo "modelc: $(VISP_MBT)/cube.cao missing: run make deps (package visp-images-data)" >&2; exit 1; }
	$(MODELC) $(VISP_MBT)/cube.cao -o $(BUILD) --name cube --as edges -q
$(BUILD)/cube/cube-track: $(BUILD)/cube/budget.json $(RT_OBJ) $(TRACK_OBJ)
	$(call link_track,cube)

# ---- demo ------------------------------------------------------------------------------------
DEMO_VIEW := $(BUILD)/$(DEFAULT_MODEL)/$(DEFAULT_MODEL)-view
demo: deps
	$(MAKE) --no-print-directory $(DEMO_VIEW)
	$(DEMO_VIEW) --png $(BUILD)/$(DEFAULT_MODEL).png --yaw 20 --pitch 10
	@python3 -c 'import json,sys; b=json.load(open("$(BUILD)/$(DEFAULT_MODEL)/budget.json")); print("points %d, data %d bytes, %.2f bits/point geometry, %.2f total" % (b["points"], b["flash"]["total"], b["bits_per_point"]["geometry"], b["bits_per_point"]["total"]))'
	@echo "wrote $(BUILD)/$(DEFAULT_MODEL).png; run $(DEMO_VIEW) in a terminal to turn it"

# the README's pictures, rendered by the viewer binaries
readme-images: $(BUILD)/bunny00/bunny00-view $(BUILD)/nefertiti/nefertiti-view $(BUILD)/cube/cube-track $(BUILD)/bunny00/budget.json
	$(BUILD)/bunny00/bunny00-view --png models/img/bunny00.png --zoom 0.9 --yaw 25 --pitch 10
	rm -rf $(BUILD)/cube/overlay && mkdir -p $(BUILD)/cube/overlay
	$(BUILD)/cube/cube-track --frames '$(VISP_MBT)/cube/image%04d.pgm' --camera $(VISP_MBT)/cube.xml \
	  --init $(VISP_MBT)/cube.0.pos --count 31 --out $(BUILD)/cube/poses.csv --overlay $(BUILD)/cube/overlay
	cp $(BUILD)/cube/overlay/frame0030.png models/img/cube_track.png
	$(BUILD)/nefertiti/nefertiti-view --png models/img/nefertiti.png --zoom 0.85 --yaw -30 --pitch 5
	$(MAKE) --no-print-directory $(BUILD)/bunny00/web/index.html
	python3 tests/web/cdp.py file://$(CURDIR)/$(BUILD)/bunny00/web/index.html --size 672x560 \
	  --eval-file tests/web/pose.js --screenshot models/img/web.png
	$(MAKE) --no-print-directory view MODEL=$(BUILD)/models/bunny00.off NAME=bunny00_mesh BAKE_OPTS="--as both"
	for m in shaded lines shaded+lines; do \
	  $(BUILD)/bunny00_mesh/bunny00_mesh-view --mode $$m --png models/img/bunny00_$$(echo $$m | tr + _).png \
	    --zoom 0.9 --yaw 25 --pitch 10; done

# ---- tests and benchmarks --------------------------------------------------------------------
test:
	@tests/run.sh

bench: $(MODELC) models
	@tests/bench/run.sh
	@tests/bench/views.sh
	@tests/bench/web.sh

# run time against error: depth 5..10, MC_FRAC_BITS 8..24, the float build (tests/accuracy/pos_single.h) and
# exact double-precision positions against the mesh reference: tests/bench/accuracy.{csv,png} and a RESULTS.md section (tests/accuracy/bench.sh)
# the progressive mesh: level changes against OpenMesh's vertex splits, flash per split against its
# .pm file (a RESULTS.md section; make bench runs it too)
.PHONY: bench-pmesh
bench-pmesh: $(MODELC) models
	@tests/bench/pmesh.sh

# filled triangles: mc_mesh_render against Mesa's llvmpipe on one thread (OSMesa), the same triangles
# and view, coverage masks compared (a RESULTS.md section; make bench runs it too)
.PHONY: bench-mesh
bench-mesh: $(MODELC) models
	@tests/bench/mesh.sh

# the point renderer's two walks over 2x2 squares (config.h MC_FLAT_SQUARES) side by side: instructions
# per point and CPU time (a RESULTS.md section; make bench runs it too)
.PHONY: bench-squares
bench-squares: $(MODELC) models
	@tests/bench/flat_squares.sh

# the probabilistic silhouette search against the exact scan: recall and instructions (a RESULTS.md
# section and tests/bench/silhouette.png; make bench runs it too)
.PHONY: bench-silhouette
bench-silhouette: $(MODELC) models
	@tests/bench/silhouette.sh

# the tracker's particle filter on a synthetic cube sequence: ms and instructions per frame and per
# pose, pose errors, as the particle count and frame size vary (a RESULTS.md section; make bench runs it too)
.PHONY: bench-track
bench-track:
	@tests/bench/track.sh
	@tests/bench/line_select.sh
	@tests/bench/track_seq.sh

# ViSP's model-based edge tracker (vpMbGenericTracker, edges only) on ViSP's cube sequence: the peer of
# build/cube/cube-track, same CSV (needs make deps-bench: libvisp-dev; compare with tests/bench/cube_compare.py)
VISP_CFLAGS = $(shell pkg-config --cflags visp 2>/dev/null)
VISP_LIBS := -lvisp_mbt -lvisp_me -lvisp_io -lvisp_core
$(BUILD)/bench/visp_track: tests/bench/visp_track.cpp
	@pkg-config --exists visp || { echo "modelc: ViSP (libvisp-dev) missing: run make deps-bench" >&2; exit 1; }
	@mkdir -p $(@D)
	g++ -O2 -g -std=c++17 -Wall -Wextra $(VISP_CFLAGS) -o $@ $< $(VISP_LIBS)

# preloaded into visp_track under callgrind only: see the file's header
$(BUILD)/bench/hwy_timer_stub.so: tests/bench/hwy_timer_stub.c
	@mkdir -p $(@D)
	gcc -O2 -Wall -Wextra -shared -fPIC -o $@ $<

# the automatic level of detail holding frame-time targets (a RESULTS.md section; make bench runs it too)
.PHONY: bench-lod-auto
bench-lod-auto: $(MODELC) models
	@tests/bench/lod_auto.sh

# line drawings at coarse levels without and with the level's neighbour table (--mesh-neighbours),
# side by side, and what the table costs a level change (a RESULTS.md section; make bench runs it too)
.PHONY: bench-neighbours
bench-neighbours: $(MODELC) models
	@tests/bench/neighbours.sh

# face groups' normal cones against random views: what a hierarchy could spare the line drawings'
# passes over every face (an analysis of the meshes' geometry)
.PHONY: bench-cones
bench-cones: $(MODELC) models
	@tests/bench/cone_groups.sh

# run time against error for the mesh's level of detail: shaded frames at 1-100 % of the faces against
# the full level (PSNR, coverage), time and instructions per frame (a RESULTS.md section,
# tests/bench/lod_error.png and tests/bench/lod_strip.png; make bench runs it too)
.PHONY: bench-lod-error
bench-lod-error: $(MODELC) models
	@tests/bench/lod_error.sh

# the point renderer at every view: zoom 0.25, 640x480, perspective, the depth-9 and depth-10 bakes, with the
# screen-space level of detail on and off; instructions per frame and per drawn leaf, ms beside Mesa llvmpipe
# on one thread, PSNR against the mesh reference (a RESULTS.md section; make bench runs it too, after run.sh)
.PHONY: bench-views
bench-views: $(MODELC) models
	@tests/bench/views.sh

.PHONY: bench-web
bench-web: $(MODELC) models
	@tests/bench/web.sh

.PHONY: bench-accuracy
bench-accuracy: $(MODELC) models
	@tests/accuracy/bench.sh

# 10^7 random views (tests/stress/stress.c), on two processes with their own seeds, plus the F=8/24
# and ASan + UBSan runs of tests/stress/suite.sh
STRESS_VIEWS ?= 10000000
# and the freestanding builds of the runtime at every optimisation level, the leaf switch at each
# (make test: -O0 -O2 -Os on the Cortex-M0, fewer on x86-64, the switch at -O2), and the unit tests
# under the sanitizers at every MC_FRAC_BITS the plain run tests (make test: the default), and the
# renders with the leaf switch under the sanitizers (make test: the loop form there), the
# generator suite with a depth-10 bake's levels checked too, and every point set of tests/points
stress: $(MODELC) $(BUILD)/models/bunny00.off
	@STRESS_VIEWS=$(STRESS_VIEWS) STRESS_JOBS=2 STRESS_F_VIEWS=100000 STRESS_SAN_VIEWS=10000 STRESS_ALT_SWITCH=1 tests/stress/suite.sh; s=$$?; \
	  UNIT_SWITCH_ALL=1 UNIT_OPT_LEVELS="-O0 -O1 -O2 -O3 -Os" tests/unit/suite.sh || s=1; \
	  SANITIZE=1 UNIT_SAN_FORMATS="15 8 24" tests/unit/suite.sh || s=1; \
	  SANITIZE=1 RENDER_SAN_SWITCH=1 tests/render/suite.sh || s=1; \
	  GEN_DEEP=1 tests/gen/suite.sh || s=1; \
	  POINTS_ALL=1 tests/points/suite.sh || s=1; exit $$s

clean:
	rm -rf $(BUILD)

# ---- fuzzing: tests/fuzz/ (README there) -------------------------------------------------------
# Every generator source but gen/main.cpp, compiled by clang with coverage for libFuzzer, ASan and
# UBSan; one target per reader (tests/fuzz/fuzz_reader.cpp with the extension compiled in) and one
# for the whole bake (tests/fuzz/fuzz_bake.cpp, with gen/main.cpp's main renamed so it is callable).
# gltf and glb are the glTF reader's two forms; tinygltf and stb_image are compiled in from their
# headers (tests/fuzz/tinygltf_impl.cpp) so that they are instrumented too, not linked as -ltinygltf -lstb.
#   make fuzz [FUZZ_SECONDS=600] [FUZZ_TARGETS="off obj ply stl xyz cao gltf glb bake track_input stream"]   findings: tests/fuzz/regress/
FUZZ_CXX ?= clang++
FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_CXXFLAGS := -O1 -g $(FUZZ_SAN) -fsanitize=fuzzer-no-link $(GEN_CXXFLAGS) -DMC_OPENMESH_ASSERTS=1
FUZZ_READERS := off obj ply stl xyz cao gltf glb
FUZZ_TARGETS ?= $(FUZZ_READERS) bake track_input stream
FUZZ_SECONDS ?= 600
FUZZ_DIR := $(BUILD)/fuzz
FUZZ_GEN_SRC := $(filter-out gen/main.cpp,$(GEN_SRC))
FUZZ_GEN_OBJ := $(patsubst gen/%.cpp,$(FUZZ_DIR)/gen/%.o,$(FUZZ_GEN_SRC)) $(FUZZ_DIR)/gen/templates.o $(FUZZ_DIR)/tinygltf.o
FUZZ_LIBS := $(filter-out -ltinygltf -lstb,$(GEN_LIBS))
FUZZ_BINS := $(foreach t,$(FUZZ_TARGETS),$(FUZZ_DIR)/fuzz-$(t))
$(FUZZ_DIR)/gen/%.o: gen/%.cpp $(GEN_HDR)
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -c -o $@ $<
$(FUZZ_DIR)/gen/templates.o: $(BUILD)/gen/templates.cpp
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -c -o $@ $<
$(FUZZ_DIR)/tinygltf.o: tests/fuzz/tinygltf_impl.cpp
	@mkdir -p $(@D)
	$(FUZZ_CXX) -O1 -g $(FUZZ_SAN) -fsanitize=fuzzer-no-link -std=c++17 -w -I/usr/include/stb -c -o $@ $<
$(FUZZ_DIR)/main.o: gen/main.cpp $(GEN_HDR)
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -Dmain=mc_fuzz_modelc_main -c -o $@ $<
$(FUZZ_DIR)/reader-%.o: tests/fuzz/fuzz_reader.cpp tests/fuzz/fuzz_file.hpp $(GEN_HDR)
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -DMC_FUZZ_EXT='"$*"' -c -o $@ $<
$(FUZZ_DIR)/bake.o: tests/fuzz/fuzz_bake.cpp tests/fuzz/fuzz_file.hpp $(GEN_HDR)
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_CXXFLAGS) -c -o $@ $<
$(foreach r,$(FUZZ_READERS),$(FUZZ_DIR)/fuzz-$(r)): $(FUZZ_DIR)/fuzz-%: $(FUZZ_DIR)/reader-%.o $(FUZZ_GEN_OBJ)
	$(FUZZ_CXX) $(FUZZ_SAN) -fsanitize=fuzzer -o $@ $^ $(FUZZ_LIBS)
$(FUZZ_DIR)/fuzz-bake: $(FUZZ_DIR)/bake.o $(FUZZ_DIR)/main.o $(FUZZ_GEN_OBJ)
	$(FUZZ_CXX) $(FUZZ_SAN) -fsanitize=fuzzer -o $@ $^ $(FUZZ_LIBS)
# the tracker front end's input readers (runtime/front/track/track_input.c: C, so clang); its
# findings are replayed by tests/unit/test_track_input.c, not through modelc
FUZZ_CC ?= clang
$(FUZZ_DIR)/fuzz-track_input: tests/fuzz/fuzz_track_input.c runtime/front/track/track_input.c runtime/front/track/track_input.h
	@mkdir -p $(@D)
	$(FUZZ_CC) -O1 -g $(FUZZ_SAN) -fsanitize=fuzzer -Wall -Wextra -Werror -Iruntime/include -o $@ \
	  tests/fuzz/fuzz_track_input.c runtime/front/track/track_input.c -lm

# the stream reader (runtime/src/stream.c, stream_mesh.c, stream_packed.c: C) and the renderers on what it
# takes; its findings are replayed by tests/stream/suite.sh. The octree renderer's leaves in their loop
# form (MC_LEAF_SWITCH=0: the same per-leaf code, as tests/stream/suite.sh builds it; the switch takes
# clang's sanitizers over half an hour to compile)
$(FUZZ_DIR)/fuzz-stream: tests/fuzz/fuzz_stream.c tests/stream/forge.h runtime/front/common/mesh_frame.c $(RT_SRC) $(RT_HDR)
	@mkdir -p $(@D)
	$(FUZZ_CC) -O1 -g $(FUZZ_SAN) -fsanitize=fuzzer -DMC_LEAF_SWITCH=0 -Wall -Wextra -Werror -Iruntime/include -o $@ \
	  tests/fuzz/fuzz_stream.c runtime/front/common/mesh_frame.c $(RT_SRC)

.PHONY: fuzz fuzz-build
fuzz-build: $(FUZZ_BINS)
# first the generator built with g++'s ASan + UBSan (tests/sanitize/suite.sh SAN_PARTS=generator: the
# error table, the findings and a real bake, compared with the normal generator's), then the fuzzers
fuzz: fuzz-build models $(MODELC) $(BUILD)/nefertiti/budget.json
	@SAN_PARTS=generator tests/sanitize/suite.sh; s=$$?; \
	  FUZZ_SECONDS=$(FUZZ_SECONDS) tests/fuzz/fuzz.sh $(FUZZ_TARGETS) && exit $$s

# ---- firmware: Cortex-M images run under QEMU ---------------------------------------------
#   make firmware MODEL=m BOARD=b      bake catalogue model m for board b, cross-compile, check the ELF
#   make firmware-run MODEL=m BOARD=b  run it under qemu-system-arm; compare its checksums with the host's
#   make bench-firmware                instructions per frame and per point under QEMU (RESULTS.md section)
#   make firmware[-run] FW_MESH=1 ...  the same with the model's mesh part (--as both) at the board's mesh bake
# Boards: runtime/front/fw/boards/B.mk (CPU flags, QEMU machine, default bake depth and screen; the
# mesh bake's screen, faces and options) and B.ld (flash/RAM map for picolibc.ld). FW_DEPTH= and
# FW_SCREEN= override the board's bake. FW_MESH=1 adds the mesh part, --max-faces FW_MESH_FACES (the
# board's mesh_faces; 0: all), at the board's mesh_screen; the firmware then draws the mesh frames
# (runtime/front/common/mesh_frames.h) after the point frames. A mesh bake lives in build/fw/B-mesh/.
FW_BOARDS := $(patsubst runtime/front/fw/boards/%.mk,%,$(wildcard runtime/front/fw/boards/*.mk))
include $(wildcard runtime/front/fw/boards/*.mk)
BOARD ?= lm3s6965evb
FW_MODEL := $(or $(MODEL),$(DEFAULT_MODEL))
FW_MESH ?=
FW_DEPTH ?= $(or $(if $(FW_MESH),$($(BOARD).mesh_depth)),$($(BOARD).depth))
FW_SCREEN ?= $(or $(if $(FW_MESH),$($(BOARD).mesh_screen)),$($(BOARD).screen))
FW_MESH_FACES ?= $($(BOARD).mesh_faces)
FW_DIR := $(BUILD)/fw/$(BOARD)$(if $(FW_MESH),-mesh)
FW_BAKE := $(FW_DIR)/$(FW_MODEL)
FW_ELF := $(FW_DIR)/$(FW_MODEL).elf
FW_HOSTVIEW := $(FW_BAKE)/$(FW_MODEL)-view
FW_QEMU_TIMEOUT ?= 600
ARM_CC := arm-none-eabi-gcc
FW_SRC := $(filter-out runtime/front/fw/track_main.c runtime/front/fw/stream_main.c runtime/front/fw/uart_%.c,$(wildcard runtime/front/fw/*.c)) $(COMMON_SRC)
FW_HDR := $(wildcard runtime/front/fw/*.h) $(COMMON_HDR)
# the catalogue's bake options without its --depth, then the board's depth and screen (and mesh part)
FW_BAKE_OPTS = $(strip $(shell echo ' $($(FW_MODEL).opts) ' | sed 's/ --depth [0-9]* / /') --depth $(FW_DEPTH) \
  --screen $(FW_SCREEN) $(if $(FW_MESH),--as both --max-faces $(or $(FW_MESH_FACES),0) $($(BOARD).mesh_opts)))
# -fstack-usage and -fcallgraph-info give runtime/front/fw/stack_bound.py the frames and the call graph;
# integer-only printf keeps picolibc's float formatting out of flash; MC_FW_MESH=1 only with FW_MESH, so
# that a points-only firmware links no mesh code (budget.json counts none for it)
FW_CFLAGS := $($(BOARD).cpu) -O2 -g -ffunction-sections -fdata-sections -fstack-usage -fcallgraph-info=su \
  --specs=picolibc.specs -DPICOLIBC_INTEGER_PRINTF_SCANF $(if $(FW_MESH),-DMC_FW_MESH=1)
FW_LDFLAGS := $($(BOARD).cpu) --specs=picolibc.specs --oslib=semihost --crt0=hosted -DPICOLIBC_INTEGER_PRINTF_SCANF \
  -Truntime/front/fw/boards/$(BOARD).ld -Wl,--print-memory-usage -Wl,--gc-sections \
  -Wl,--wrap=malloc,--wrap=calloc,--wrap=realloc,--wrap=free -Wl,-Map=$(FW_DIR)/$(FW_MODEL).map
FW_QEMU = timeout $(FW_QEMU_TIMEOUT) qemu-system-arm -M $($(BOARD).qemu) -nographic -monitor none \
  -semihosting-config enable=on,target=native,arg=$(FW_MODEL),arg=$(FW_DIR)/$(FW_MODEL).ppm -kernel $(FW_ELF)

.PHONY: firmware firmware-run firmware-host bench-firmware fw-args FORCE
fw_usage = { echo "usage: make firmware|firmware-run MODEL=<catalogue model: $(CATALOGUE)> BOARD=<$(FW_BOARDS)>" >&2; exit 2; }
fw-args:
	@test -n "$(filter $(BOARD),$(FW_BOARDS))" -a -n "$(filter $(FW_MODEL),$(CATALOGUE))" || $(fw_usage)

# the bake is redone when its options change (e.g. FW_DEPTH=6)
$(FW_DIR)/$(FW_MODEL).opts: FORCE
	@mkdir -p $(@D)
	@echo '$(FW_BAKE_OPTS)' | cmp -s - $@ || echo '$(FW_BAKE_OPTS)' > $@
$(FW_BAKE)/budget.json: $(BUILD)/models/$(notdir $($(FW_MODEL).src)) $(MODELC) $(FW_DIR)/$(FW_MODEL).opts
	rm -rf $(FW_BAKE)
	$(MODELC) $< -o $(FW_DIR) --name $(FW_MODEL) -q $(FW_BAKE_OPTS)

# runtime (freestanding), firmware front end and the bake, compiled for the board, then linked
$(FW_ELF): $(FW_BAKE)/budget.json $(RT_SRC) $(RT_HDR) $(FW_SRC) $(FW_HDR) \
  runtime/front/fw/boards/$(BOARD).ld runtime/front/fw/boards/$(BOARD).mk Makefile
	@rm -rf $(FW_DIR)/obj && mkdir -p $(FW_DIR)/obj
	@set -e; o=$(FW_DIR)/obj; \
	for f in $(RT_SRC); do echo "  ARM CC $$f"; \
	  $(ARM_CC) $(FW_CFLAGS) $(RT_CFLAGS) -c -o $$o/rt_$$(basename $$f .c).o $$f; done; \
	for f in $(FW_SRC); do echo "  ARM CC $$f"; \
	  $(ARM_CC) $(FW_CFLAGS) $(HOST_CFLAGS) -c -o $$o/fw_$$(basename $$f .c).o $$f; done; \
	for f in $(FW_BAKE)/*.c; do echo "  ARM CC $$f"; \
	  $(ARM_CC) $(FW_CFLAGS) $(RT_CFLAGS) -c -o $$o/model_$$(basename $$f .c).o $$f; done
	$(ARM_CC) -o $@ $(FW_DIR)/obj/*.o $(FW_LDFLAGS)

# the host viewer linked with the same bake: --checksums prints what the firmware must print
$(FW_HOSTVIEW): $(FW_BAKE)/budget.json $(RT_OBJ) $(HOST_OBJ)
	$(CC) $(CFLAGS) $(RT_CFLAGS) -ffunction-sections -fdata-sections -o $@ $(FW_BAKE)/*.c $(RT_OBJ) $(HOST_OBJ) $(VIEW_LDFLAGS)

# after linking: no heap, ELF against budget.json, stack bound against the board's RAM
firmware: fw-args $(FW_ELF)
	python3 runtime/front/fw/check_elf.py --elf $(FW_ELF) --budget $(FW_BAKE)/budget.json \
	  --ld runtime/front/fw/boards/$(BOARD).ld --obj $(FW_DIR)/obj --depth $(FW_DEPTH)

firmware-host: fw-args $(FW_HOSTVIEW)

firmware-run: firmware $(FW_HOSTVIEW)
	@rm -f $(FW_DIR)/$(FW_MODEL).ppm
	$(FW_QEMU) < /dev/null 2>&1 | tee $(FW_DIR)/$(FW_MODEL).run.txt
	@$(FW_HOSTVIEW) --checksums --ppm $(FW_DIR)/$(FW_MODEL).host.ppm > $(FW_DIR)/$(FW_MODEL).host.txt
	@grep -E '^(mesh )?frame ' $(FW_DIR)/$(FW_MODEL).run.txt > $(FW_DIR)/$(FW_MODEL).fw-frames.txt || true
	@if cmp -s $(FW_DIR)/$(FW_MODEL).fw-frames.txt $(FW_DIR)/$(FW_MODEL).host.txt && \
	    cmp -s $(FW_DIR)/$(FW_MODEL).ppm $(FW_DIR)/$(FW_MODEL).host.ppm; then \
	  echo "firmware-run: all $$(wc -l < $(FW_DIR)/$(FW_MODEL).host.txt) frame checksums and the written frame equal the host viewer's"; \
	else echo "firmware-run: firmware and host differ:" >&2; \
	  diff $(FW_DIR)/$(FW_MODEL).fw-frames.txt $(FW_DIR)/$(FW_MODEL).host.txt >&2; exit 1; fi

bench-firmware:
	@tests/fw/bench.sh

# ---- the model over the UART: a receiver firmware under QEMU ------------------------------------
#   make firmware-stream BOARD=b [FW_MESH=1]     bake the board's stream, build the receiver, check the ELF
#   make firmware-stream-run BOARD=b [STREAM=f]  run it under qemu-system-arm with UART0 fed from file f
#                                                (default: the bake's NAME.mcs); compare with the host viewer
# The receiver (runtime/front/fw/stream_main.c and the board's UART driver, uart_$(B.uart).c) links no
# model arrays: the bake (build/fw/B-stream/NAME: --emit stream at the board's stream_depth and
# stream_screen, boards/B.mk) gives it only NAME.h's sizes, for its static receive and frame buffers.
# QEMU reads f on its standard input (-serial stdio; QEMU 7.2's file chardev takes no input-path)
# and hands UART0 a byte only when it has room, so nothing is lost; a UART has no end of file, so the
# firmware ends a stream that stops short after idle=MS without a byte (FW_STREAM_ARGS: its options,
# e.g. "idle=3000 frames=4"). FW_STREAM_SERIAL replaces -serial stdio (e.g. -serial tcp::4444,server
# for a sender on a socket; the comparison still reads f). runtime/front/fw/stream_check.py then
# compares the firmware's lines with the host viewer linked with the same bake: each level's frames
# with --checksums --depth D and with --stream on the bytes the firmware had when it drew them, the
# final state (complete, or the reader's error, its byte and the depth kept) with --stream f's.
# FW_MESH=1: the bake --as both, its mesh capped at the board's stream_mesh_faces, its splits
# FW_STREAM_SPLITS (the board's stream_splits: plain or packed), the octree at stream_mesh_depth; the
# receiver also draws the mesh frames once the mesh has come (stream_main.c). It lives in
# build/fw/B-stream-mesh/.
FW_STREAM_DEPTH ?= $(or $(if $(FW_MESH),$($(BOARD).stream_mesh_depth)),$($(BOARD).stream_depth))
FW_STREAM_SCREEN ?= $($(BOARD).stream_screen)
FW_STREAM_SPLITS ?= $($(BOARD).stream_splits)
FW_STREAM_DIR := $(BUILD)/fw/$(BOARD)-stream$(if $(FW_MESH),-mesh)
FW_STREAM_BAKE := $(FW_STREAM_DIR)/$(FW_MODEL)
FW_STREAM_ELF := $(FW_STREAM_DIR)/$(FW_MODEL)-stream.elf
FW_STREAM_VIEW := $(FW_STREAM_BAKE)/$(FW_MODEL)-view
STREAM ?= $(FW_STREAM_BAKE)/$(FW_MODEL).mcs
FW_STREAM_ARGS ?=
FW_STREAM_SRC = runtime/front/fw/stream_main.c runtime/front/fw/uart_$($(BOARD).uart).c runtime/front/fw/cmdline.c \
  runtime/front/fw/stack.c
FW_STREAM_BAKE_OPTS = $(strip $(shell echo ' $($(FW_MODEL).opts) ' | sed 's/ --depth [0-9]* / /') --depth $(FW_STREAM_DEPTH) \
  --screen $(FW_STREAM_SCREEN) --emit stream \
  $(if $(FW_MESH),--as both --max-faces $($(BOARD).stream_mesh_faces) --stream-splits $(FW_STREAM_SPLITS)))
# the bake's NAME.h defines, by name: MC_<NAME>_STREAM_BYTES, _SCREEN_WIDTH, _SCREEN_HEIGHT, _DEPTH
# (and the mesh part's _PMESH_VERTICES, _PMESH_LOD_BYTES, _PMESH_FACING_BYTES)
fw_stream_def = MC_$(shell echo '$(FW_MODEL)' | tr a-z A-Z)_$(1)
FW_STREAM_CFLAGS = -I$(FW_STREAM_BAKE) -DMC_FW_STREAM_HEADER='"$(FW_MODEL).h"' -DMC_FW_CLOCK_HZ=$($(BOARD).clock_hz)u \
  -DMC_FW_STREAM_BYTES=$(call fw_stream_def,STREAM_BYTES) -DMC_FW_STREAM_WIDTH=$(call fw_stream_def,SCREEN_WIDTH) \
  -DMC_FW_STREAM_HEIGHT=$(call fw_stream_def,SCREEN_HEIGHT) -DMC_FW_STREAM_DEPTH=$(call fw_stream_def,DEPTH) \
  $(if $(FW_MESH),-DMC_FW_STREAM_MESH=1 -DMC_FW_STREAM_PMESH_VERTICES=$(call fw_stream_def,PMESH_VERTICES) \
    -DMC_FW_STREAM_PMESH_LOD_BYTES=$(call fw_stream_def,PMESH_LOD_BYTES) \
    -DMC_FW_STREAM_PMESH_FACING_BYTES=$(call fw_stream_def,PMESH_FACING_BYTES))
FW_STREAM_LDFLAGS = $(subst $(FW_DIR)/$(FW_MODEL).map,$(FW_STREAM_DIR)/$(FW_MODEL)-stream.map,$(FW_LDFLAGS))
comma := ,
FW_STREAM_SERIAL ?= -serial stdio
FW_STREAM_QEMU = timeout $(FW_QEMU_TIMEOUT) qemu-system-arm -M $($(BOARD).qemu) -nographic -monitor none \
  -semihosting-config enable=on,target=native,arg=$(FW_MODEL)-stream$(foreach a,$(FW_STREAM_ARGS),$(comma)arg=$(a)) \
  $(FW_STREAM_SERIAL) -kernel $(FW_STREAM_ELF)

.PHONY: firmware-stream firmware-stream-run fw-stream-args
fw-stream-args:
	@test -n "$(filter $(BOARD),$(FW_BOARDS))" -a -n "$(filter $(FW_MODEL),$(CATALOGUE))" -a -n "$($(BOARD).uart)" || \
	  { echo "usage: make firmware-stream|firmware-stream-run MODEL=<$(CATALOGUE)> BOARD=<$(FW_BOARDS)> [STREAM=file]" >&2; exit 2; }

$(FW_STREAM_DIR)/$(FW_MODEL).opts: FORCE
	@mkdir -p $(@D)
	@echo '$(FW_STREAM_BAKE_OPTS)' | cmp -s - $@ || echo '$(FW_STREAM_BAKE_OPTS)' > $@
$(FW_STREAM_BAKE)/budget.json: $(BUILD)/models/$(notdir $($(FW_MODEL).src)) $(MODELC) $(FW_STREAM_DIR)/$(FW_MODEL).opts
	rm -rf $(FW_STREAM_BAKE)
	$(MODELC) $< -o $(FW_STREAM_DIR) --name $(FW_MODEL) -q $(FW_STREAM_BAKE_OPTS)

# the runtime and the receiver only (the bake's .c files are not compiled), an object a source so
# that make -j compiles them side by side
FW_STREAM_RT_OBJ = $(patsubst runtime/src/%.c,$(FW_STREAM_DIR)/obj/rt_%.o,$(RT_SRC))
FW_STREAM_FW_OBJ = $(patsubst runtime/front/fw/%.c,$(FW_STREAM_DIR)/obj/fw_%.o,$(FW_STREAM_SRC))
FW_STREAM_DEPS = $(RT_HDR) runtime/front/fw/boards/$(BOARD).mk Makefile
$(FW_STREAM_RT_OBJ): $(FW_STREAM_DIR)/obj/rt_%.o: runtime/src/%.c $(FW_STREAM_DEPS)
	@mkdir -p $(@D)
	@echo "  ARM CC $<"
	@$(ARM_CC) $(FW_CFLAGS) $(RT_CFLAGS) -c -o $@ $<
$(FW_STREAM_FW_OBJ): $(FW_STREAM_DIR)/obj/fw_%.o: runtime/front/fw/%.c $(FW_STREAM_DEPS) $(FW_HDR) $(FW_STREAM_BAKE)/budget.json
	@mkdir -p $(@D)
	@echo "  ARM CC $<"
	@$(ARM_CC) $(FW_CFLAGS) $(HOST_CFLAGS) $(FW_STREAM_CFLAGS) -c -o $@ $<
# with a mesh, the mesh frames' sequence too (runtime/front/common/mesh_frame.c)
FW_STREAM_MESH_OBJ = $(if $(FW_MESH),$(FW_STREAM_DIR)/obj/common_mesh_frame.o)
$(FW_STREAM_DIR)/obj/common_mesh_frame.o: runtime/front/common/mesh_frame.c $(FW_STREAM_DEPS) $(FW_HDR)
	@mkdir -p $(@D)
	@echo "  ARM CC $<"
	@$(ARM_CC) $(FW_CFLAGS) $(HOST_CFLAGS) -c -o $@ $<
$(FW_STREAM_ELF): $(FW_STREAM_RT_OBJ) $(FW_STREAM_FW_OBJ) $(FW_STREAM_MESH_OBJ) runtime/front/fw/boards/$(BOARD).ld
	$(ARM_CC) -o $@ $(FW_STREAM_RT_OBJ) $(FW_STREAM_FW_OBJ) $(FW_STREAM_MESH_OBJ) $(FW_STREAM_LDFLAGS)

$(FW_STREAM_VIEW): $(FW_STREAM_BAKE)/budget.json $(RT_OBJ) $(HOST_OBJ)
	$(CC) $(CFLAGS) $(RT_CFLAGS) -ffunction-sections -fdata-sections -o $@ $(FW_STREAM_BAKE)/*.c $(RT_OBJ) $(HOST_OBJ) $(VIEW_LDFLAGS)

firmware-stream: fw-stream-args $(FW_STREAM_ELF)
	arm-none-eabi-size $(FW_STREAM_ELF)
	python3 runtime/front/fw/check_stream_elf.py --elf $(FW_STREAM_ELF) --budget $(FW_STREAM_BAKE)/budget.json \
	  --ld runtime/front/fw/boards/$(BOARD).ld --obj $(FW_STREAM_DIR)/obj

firmware-stream-run: firmware-stream $(FW_STREAM_VIEW)
	@test -f '$(STREAM)' || { echo "firmware-stream-run: STREAM=$(STREAM): no such file" >&2; exit 2; }
	@rm -f $(FW_STREAM_DIR)/run.txt; $(FW_STREAM_QEMU) < '$(STREAM)' > $(FW_STREAM_DIR)/run.txt 2>&1; \
	  st=$$?; cat $(FW_STREAM_DIR)/run.txt; \
	  python3 runtime/front/fw/stream_check.py --run $(FW_STREAM_DIR)/run.txt --status $$st \
	    --view $(FW_STREAM_VIEW) --stream '$(STREAM)' --work $(FW_STREAM_DIR)/check

# ---- the tracker on Cortex-M: ViSP's cube under QEMU, its poses equal to the host tracker's ------
#   make firmware-track BOARD=b        bake ViSP's cube (--as edges) for board b, store frames of its sequence, cross-compile, check the ELF
#   make firmware-track-run BOARD=b    run it under qemu-system-arm; compare its poses with the host tracker's on the same frames
#   make bench-firmware-track          Cortex-M4 instructions per frame and per particle under QEMU, edges and filter
# The bake (build/fw/B-track/cube): --screen FW_TRACK_SCREEN and --particles FW_TRACK_PARTICLES (100):
# 160x120 (the frames shrunk 4 times, 111 KB of RAM), on lm3s6965evb 106x80 (6 times: 160x120 needs
# 111 KB of its 64 KiB RAM; 106x80 55 KB, beside the 3840-byte stack reservation).
# runtime/front/fw/track_frames.py shrinks FW_TRACK_FRAMES frames from FW_TRACK_FIRST of the real
# sequence on the host into a generated C file (build/fw/B-track/frames.c, linked into the firmware:
# runtime/front/fw/track_main.c), and writes the same frames as PGM files with the host tracker's
# arguments (frames/host-args: --shrunk K, the same camera, start pose and particles); the host
# tracker linked with the same bake (build/fw/B-track/cube/cube-track) runs on those with --fixed-out.
FW_TRACK_SCREEN ?= $(if $(filter lm3s6965evb,$(BOARD)),106x80,160x120)
FW_TRACK_PARTICLES ?= 100
FW_TRACK_FIRST ?= 0
FW_TRACK_FRAMES ?= 8
FW_TRACK_DIR := $(BUILD)/fw/$(BOARD)-track
FW_TRACK_BAKE := $(FW_TRACK_DIR)/cube
FW_TRACK_ELF := $(FW_TRACK_DIR)/cube-track.elf
FW_TRACK_HOST := $(FW_TRACK_BAKE)/cube-track
FW_TRACK_OPTS = --screen $(FW_TRACK_SCREEN) --particles $(FW_TRACK_PARTICLES)
FW_TRACK_SRC := runtime/front/fw/track_main.c runtime/front/fw/cmdline.c runtime/front/fw/counter.c runtime/front/fw/stack.c \
  runtime/front/common/track_frame.c runtime/front/track/track_input.c
FW_TRACK_LDFLAGS = $(subst $(FW_DIR)/$(FW_MODEL).map,$(FW_TRACK_DIR)/cube-track.map,$(FW_LDFLAGS))
FW_TRACK_QEMU = timeout $(FW_QEMU_TIMEOUT) qemu-system-arm -M $($(BOARD).qemu) -nographic -monitor none

.PHONY: firmware-track firmware-track-run bench-firmware-track fw-track-args fw-track-host fw-track-bench
fw-track-args:
	@test -n "$(filter $(BOARD),$(FW_BOARDS))" || { echo "usage: make firmware-track|firmware-track-run BOARD=<$(FW_BOARDS)>" >&2; exit 2; }
	@test -f $(VISP_MBT)/cube.cao || { echo "modelc: $(VISP_MBT)/cube.cao missing: run make deps (package visp-images-data)" >&2; exit 1; }

# the bake and the frames are redone when their options change (e.g. FW_TRACK_PARTICLES=50)
$(FW_TRACK_DIR)/opts: FORCE
	@mkdir -p $(@D)
	@echo '$(FW_TRACK_OPTS) --first $(FW_TRACK_FIRST) --count $(FW_TRACK_FRAMES)' | cmp -s - $@ || \
	  echo '$(FW_TRACK_OPTS) --first $(FW_TRACK_FIRST) --count $(FW_TRACK_FRAMES)' > $@
$(FW_TRACK_BAKE)/budget.json: $(MODELC) $(FW_TRACK_DIR)/opts
	rm -rf $(FW_TRACK_BAKE)
	$(MODELC) $(VISP_MBT)/cube.cao -o $(FW_TRACK_DIR) --name cube --as edges -q $(FW_TRACK_OPTS)
# the stored frames as C, as PGM files with the host's arguments, and budget.json with the frames counted
$(FW_TRACK_DIR)/frames.c: runtime/front/fw/track_frames.py $(FW_TRACK_BAKE)/budget.json
	rm -rf $(FW_TRACK_DIR)/frames
	python3 runtime/front/fw/track_frames.py --frames '$(VISP_MBT)/cube/image%04d.pgm' --camera $(VISP_MBT)/cube.xml \
	  --init $(VISP_MBT)/cube.0.pos --first $(FW_TRACK_FIRST) --count $(FW_TRACK_FRAMES) --screen $(FW_TRACK_SCREEN) \
	  --particles $(FW_TRACK_PARTICLES) --c $@ --pgm $(FW_TRACK_DIR)/frames \
	  --budget $(FW_TRACK_BAKE)/budget.json --budget-out $(FW_TRACK_DIR)/budget.json

# runtime (freestanding), the tracker's front end, the bake and the frames, compiled for the board, then linked
$(FW_TRACK_ELF): $(FW_TRACK_DIR)/frames.c $(FW_TRACK_BAKE)/budget.json $(RT_SRC) $(RT_HDR) $(FW_TRACK_SRC) $(FW_HDR) \
  runtime/front/track/track_input.h runtime/front/fw/boards/$(BOARD).ld runtime/front/fw/boards/$(BOARD).mk Makefile
	@rm -rf $(FW_TRACK_DIR)/obj && mkdir -p $(FW_TRACK_DIR)/obj
	@set -e; o=$(FW_TRACK_DIR)/obj; \
	for f in $(RT_SRC); do echo "  ARM CC $$f"; \
	  $(ARM_CC) $(FW_CFLAGS) $(RT_CFLAGS) -c -o $$o/rt_$$(basename $$f .c).o $$f; done; \
	for f in $(FW_TRACK_SRC); do echo "  ARM CC $$f"; \
	  $(ARM_CC) $(FW_CFLAGS) $(HOST_CFLAGS) -c -o $$o/fw_$$(basename $$f .c).o $$f; done; \
	for f in $(FW_TRACK_BAKE)/*.c $(FW_TRACK_DIR)/frames.c; do echo "  ARM CC $$f"; \
	  $(ARM_CC) $(FW_CFLAGS) $(RT_CFLAGS) -c -o $$o/model_$$(basename $$f .c).o $$f; done
	$(ARM_CC) -o $@ $(FW_TRACK_DIR)/obj/*.o $(FW_TRACK_LDFLAGS)

# the host tracker linked with the same bake: --fixed-out writes what the firmware must print
$(FW_TRACK_HOST): $(FW_TRACK_BAKE)/budget.json $(RT_OBJ) $(TRACK_OBJ)
	$(CC) $(CFLAGS) $(RT_CFLAGS) -ffunction-sections -fdata-sections -o $@ $(FW_TRACK_BAKE)/*.c $(RT_OBJ) $(TRACK_OBJ) $(VIEW_LDFLAGS)

# after linking: no heap, model arrays, buffers and stored frames against budget.json, the board, the stack
firmware-track: fw-track-args $(FW_TRACK_ELF)
	python3 runtime/front/fw/check_elf.py --elf $(FW_TRACK_ELF) --budget $(FW_TRACK_DIR)/budget.json \
	  --ld runtime/front/fw/boards/$(BOARD).ld --obj $(FW_TRACK_DIR)/obj --depth 0

firmware-track-run: firmware-track $(FW_TRACK_HOST)
	@set -o pipefail; $(FW_TRACK_QEMU) -semihosting-config enable=on,target=native,arg=cube-track \
	  -kernel $(FW_TRACK_ELF) < /dev/null 2>&1 | tee $(FW_TRACK_DIR)/run.txt
	$(FW_TRACK_HOST) $$(cat $(FW_TRACK_DIR)/frames/host-args) --out $(FW_TRACK_DIR)/host.csv \
	  --fixed-out $(FW_TRACK_DIR)/host-poses.txt
	@grep '^pose ' $(FW_TRACK_DIR)/run.txt > $(FW_TRACK_DIR)/fw-poses.txt || true
	@n=$$(wc -l < $(FW_TRACK_DIR)/host-poses.txt); \
	if grep -q '^done' $(FW_TRACK_DIR)/run.txt && [ "$$n" -eq $(FW_TRACK_FRAMES) ] && \
	    cmp -s $(FW_TRACK_DIR)/fw-poses.txt $(FW_TRACK_DIR)/host-poses.txt; then \
	  echo "firmware-track-run: all $$n poses equal the host's"; \
	else echo "firmware-track-run: firmware and host differ:" >&2; \
	  diff $(FW_TRACK_DIR)/fw-poses.txt $(FW_TRACK_DIR)/host-poses.txt >&2; exit 1; fi

# Cortex-M4 (mps2-an386) under -icount shift=0 with "bench": instructions per frame of mc_track_edges
# (the frame's copy, edges, masks) and of mc_filter_step, per particle, and the poses against the host's
bench-firmware-track:
	@tests/fw/track_bench.sh
# the table alone (tests/fw/track_bench.sh writes it into RESULTS.md)
.PHONY: fw-bench-firmware-track
fw-bench-firmware-track:
	@mkdir -p $(BUILD)/fw/mps2-an386-track
	@$(MAKE) -s --no-print-directory firmware-track fw-track-host BOARD=mps2-an386 >$(BUILD)/fw/mps2-an386-track/build.txt 2>&1 || \
	  { tail -20 $(BUILD)/fw/mps2-an386-track/build.txt; echo "bench-firmware-track: the build failed" >&2; exit 1; }
	@$(MAKE) -s --no-print-directory fw-track-bench BOARD=mps2-an386
fw-track-host: fw-track-args $(FW_TRACK_HOST)
fw-track-bench: fw-track-args
	@set -o pipefail; $(FW_TRACK_QEMU) -icount shift=0 -semihosting-config enable=on,target=native,arg=cube-track,arg=bench \
	  -kernel $(FW_TRACK_ELF) < /dev/null > $(FW_TRACK_DIR)/bench.txt 2>&1 || \
	  { tail -5 $(FW_TRACK_DIR)/bench.txt; echo "bench-firmware-track: QEMU failed" >&2; exit 1; }
	@$(FW_TRACK_HOST) $$(cat $(FW_TRACK_DIR)/frames/host-args) --fixed-out $(FW_TRACK_DIR)/host-poses.txt >/dev/null
	@grep '^pose ' $(FW_TRACK_DIR)/bench.txt | cmp -s - $(FW_TRACK_DIR)/host-poses.txt && same=yes || same=NO; \
	awk -v same=$$same -v screen=$(FW_TRACK_SCREEN) -v cpu="$(BOARD), $$(qemu-system-arm --version | head -1)" ' \
	  /^cost track/ { n++; e += $$5; f += $$7; px += $$9; p = $$11; l = $$13; \
	    r[n] = sprintf("%5d %11d %11d %9d %15.0f %15.0f", $$3, $$5, $$7, $$9, $$7 / ($$11 * $$13 + 1), ($$5 + $$7) / ($$11 * $$13 + 1)) } \
	  END { if (!n) { print "bench-firmware-track: no cost lines" > "/dev/stderr"; exit 1 } \
	    printf "bench-firmware-track: Cortex-M4 instructions (%s, -icount shift=0), cube at %s, %d particles, %d layer(s)\n", cpu, screen, p, l; \
	    printf "%5s %11s %11s %9s %15s %15s\n", "frame", "edges", "filter", "edge-px", "filter/score", "frame/score"; \
	    for (i = 1; i <= n; i++) print r[i]; \
	    printf "%5s %11.0f %11.0f %9.0f %15.0f %15.0f\n", "mean", e / n, f / n, px / n, f / n / (p * l + 1), (e + f) / n / (p * l + 1); \
	    printf "per frame: edges %.0f, filter %.0f; per scored pose (%d a frame: %d particles x %d layers + the estimate): filter %.0f; per particle: %.0f; poses equal the host tracker'"'"'s: %s\n", \
	      e / n, f / n, p * l + 1, p, l, f / n / (p * l + 1), f / n / p, same }' $(FW_TRACK_DIR)/bench.txt && [ $$same = yes ]
