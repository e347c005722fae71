# Textura - procedural texture synthesis toolkit
#
#   make            build libtex (static, shared, pkg-config), the OpenImageIO
#                   bridge and every tool under build/
#   make deps       install the Debian packages (as root)
#   make demo       run the main job: writes demo.png
#   make test       the test suite: plain and under ASan+UBSan, and gcc's maps against clang's
#   make test-clang the whole suite on a clang build (CI runs it too)
#   make bench      the benchmarks in tests/bench (not timed tests)
#   make install    PREFIX=/usr/local DESTDIR= (after a build, nothing is rebuilt
#                   for the prefix: the installed tree finds its parts at run time)
#   make uninstall  remove what make install put in PREFIX
#   make man        refresh the option lists of the man pages from the tools
#   make fuzz       build the fuzz targets (clang, libFuzzer)
#   make fuzz-libs  libpng and OpenEXR's core from Debian's sources with the fuzzer's coverage,
#                   which make fuzz then links into the targets (tests/fuzz/libs.sh)
#
# Sources are found by wildcard: a new libtex/LAYER/*.c joins the library, a new
# tools/t_*.c becomes a tool, tests/LAYER/test_*.c and tests/LAYER/*.sh join the suite.

# One job per core unless -j is given: every tree, and make test's three at once.
JOBS    ?= $(shell nproc 2>/dev/null || echo 2)
ifeq ($(MAKELEVEL)$(filter -j%,$(MAKEFLAGS)),0)
MAKEFLAGS += -j$(JOBS)
endif
# `make deps demo`: nothing compiles before the packages are in
DEPS_FIRST = $(filter deps,$(MAKECMDGOALS))

VERSION  = 0.1
PREFIX  ?= /usr/local
LIBDIR  ?= $(PREFIX)/lib
DATADIR ?= $(PREFIX)/share/textura
BUILD   ?= build
# A build tree remembers the compiler and flags it was made with (written by
# `all`), so that a later `make BUILD=build-clang install` does not relink it
# with another compiler.  Variables given on the command line still win.
-include $(BUILD)/config.mk

CC      ?= cc
CXX     ?= c++
OPT     ?= -O2
CFLAGS  ?= $(OPT) -g
CXXFLAGS ?= $(OPT) -g
WARN     = -Wall -Wextra $(if $(findstring clang,$(CC)),-Wno-pass-failed)
SANFLAGS = -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer -fno-sanitize-recover=undefined,float-cast-overflow
SAN      = $(if $(SANITIZE),$(SANFLAGS))
# the sanitizer builds compile noise.c's row kernels once for every operation (noise.c)
SAN_DEFS = $(if $(SANITIZE),-DTEX_SANITIZE)
# Frame pointers in every function, leaves too: `perf record -g` walks them, where without
# them it took whatever lay on the stack for callers (0x3ff0000000000000, a double's 1.0)
# and a profile's callers were a tail of addresses no symbol holds (doc/performance.md)
FRAMES  := -fno-omit-frame-pointer $(if $(filter x86_64 aarch64,$(shell uname -m)),-mno-omit-leaf-frame-pointer)
ALL_CFLAGS   = -std=gnu11 -fPIC -fopenmp -ffp-contract=off $(FRAMES) $(WARN) $(SAN) $(SAN_DEFS) $(CFLAGS) \
               -DTEX_VERSION='"$(VERSION)"' -DTEX_PREFIX='"$(PREFIX)"' -DTEX_LIBDIR='"$(LIBDIR)"' \
               -DTEX_DATADIR='"$(DATADIR)"'
ALL_CXXFLAGS = -std=c++17 -fPIC $(FRAMES) $(WARN) $(CXXFLAGS)
CPPFLAGS += -Ilibtex -I/usr/include/OpenEXR
LDFLAGS  += -fopenmp $(SAN) -Wl,--as-needed
LDLIBS    = -lOpenEXRCore -lfftw3f_threads -lfftw3f -llz4 -lstdc++ -lm -ldl
# FLANN is its headers' kd-tree, compiled in base/kdtree.cpp (its C API's library holds
# every index for every type: 30 page faults and 0.5 ms at every tool's start).
# Programs link libstdc++ statically: resolving its symbols at every start doubled a
# tool's start-up (6.4 ms against 2.8 ms).  FFTW,
# LZ4, libgcc and, under gcc, libgomp are static too: loading each shared library
# costs a process its mappings and page faults (7.3 ms against 6.2 ms for t_apply's
# smallest render; a fault took 11 us on the virtual machines measured here).
# OpenEXR's core has no static library in Debian.  Sanitizer builds keep everything
# shared so that ASan sees every operator new.  Programs are not position-independent
# (-no-pie): the loader would relocate every pointer in their tables (parameter rows,
# FFTW's codelets, vtables) at start, a copy-on-write fault for each of 36 pages (t_apply
# on an empty scene: 157 -> 125 faults, 4.7 -> 3.4 ms); the libraries stay where ASLR puts
# them.
GNU_CC := $(if $(findstring clang,$(shell $(CC) --version 2>/dev/null | head -1)),,1)
PROG_LDFLAGS = $(if $(SANITIZE),,-no-pie)
PROG_LDLIBS = $(if $(SANITIZE),$(LDLIBS),-static-libgcc -lOpenEXRCore -Wl,-Bstatic \
              -lfftw3f_threads -lfftw3f -llz4 -lstdc++ $(if $(GNU_CC),-lgomp) \
              -Wl,-Bdynamic -lm -ldl)

LAYERS   = base io prim ops lang render cli
# A layer's CPU-specific kernels live in its x86/ folder (FFmpeg's layout).
LIB_SRC  = $(filter-out %_template.c %_bridge.c libtex/cli/omp_env.c,$(foreach l,$(LAYERS),$(wildcard libtex/$(l)/*.c libtex/$(l)/x86/*.c)))
# Linked into every tool, not into libtex: its getenv makes OpenMP's idle threads sleep
OMP_ENV  = $(BUILD)/obj/libtex/cli/omp_env.o
# C++ in libtex: FLANN's templates (base/kdtree.cpp); the bridges are shared objects
LIB_CXX  = $(filter-out %_bridge.cpp,$(foreach l,$(LAYERS),$(wildcard libtex/$(l)/*.cpp)))
LIB_OBJ  = $(LIB_SRC:%.c=$(BUILD)/obj/%.o) $(LIB_CXX:%.cpp=$(BUILD)/obj/%.o)
TOOL_SRC = $(wildcard tools/t_*.c)
TOOLS    = $(TOOL_SRC:tools/%.c=$(BUILD)/bin/%)
# The tests follow the layers (tests/base ... tests/cli), the tools' end-to-end and the house's
# own checks beside them; a unit test's program is BUILD/tests/test_NAME.
TEST_DIRS = base io prim ops lang render cli tools house
UNIT_SRC = $(foreach d,$(TEST_DIRS),$(wildcard tests/$(d)/test_*.c))
UNITS    = $(addprefix $(BUILD)/tests/,$(basename $(notdir $(UNIT_SRC))))
BRIDGE   = $(BUILD)/lib/textura/textura-oiio.so
# One small bridge per codec library, each loaded when a file needs it.
CODECS   = png jpeg tiff
CODEC_LIBS_png = -lpng16
CODEC_LIBS_jpeg = -ljpeg
CODEC_LIBS_tiff = -ltiff
CODEC_BRIDGES = $(CODECS:%=$(BUILD)/lib/textura/textura-%.so)
STATIC   = $(BUILD)/lib/libtex.a
SHARED   = $(BUILD)/lib/libtex.so.0
PCFILE   = $(BUILD)/lib/pkgconfig/textura.pc
# Headers that stay inside libtex: the scene's internals, the shading models'
# interface, the languages' lexer and evaluator, the OpenImageIO bridge, and what a
# module's files and its x86 kernels share (trig's polynomials, the sRGB table, the noise
# tables and grids, the nearest-point queries, the solid textures' cells).  (The x86/ folders' headers are never
# installed.)
RENDER_PRIVATE = scene camera whitted vecmath shape bvh light texture surface mipmap mapping \
                 footprint appfn packet render_shade render_ct anisotropic hypertexture volume box4
PRIVATE_HEADERS = libtex/base/kdtree.h libtex/base/names.h libtex/base/nearest.h libtex/base/trig_fdlibm.h libtex/base/simd.h \
                  libtex/base/fp_strict.h libtex/io/json.h libtex/io/planes.h libtex/io/strbuf.h libtex/io/oiio_bridge.h \
                  libtex/io/codec_bridge.h libtex/prim/noise_grid.h libtex/prim/cellular_impl.h libtex/prim/cell.h \
                  libtex/ops/palette_srgb.h \
                  libtex/lang/lex.h libtex/lang/expr.h libtex/lang/rowcode.h \
                  libtex/cli/internal.h $(RENDER_PRIVATE:%=libtex/render/%.h)
HEADERS  = $(filter-out $(PRIVATE_HEADERS),$(wildcard libtex/*/*.h)) libtex/prim/primitives.def

DEBS = build-essential pkg-config liblz4-dev libopenexr-dev libopenimageio-dev openimageio-tools \
       libpng-dev libjpeg62-turbo-dev libtiff-dev libvips-dev \
       libflann-dev libfftw3-dev colord-data mandoc netpbm imagemagick libnoise-dev povray \
       hyperfine clang libclang-rt-14-dev libomp-dev python3 parallel libmicrohttpd-dev chromium ffmpeg \
       fonts-dejavu-core

.PHONY: all deps demo test test-plain test-clang check bench install uninstall man fuzz fuzz-libs fuzz-smoke figures \
        gallery clean tsan

# layout: build/share/textura holds links to the data, so that a build tree is laid
# out as an install is and finds its data files the same way (paths.h).
all: $(STATIC) $(SHARED) $(BRIDGE) $(CODEC_BRIDGES) $(PCFILE) $(TOOLS) layout

.PHONY: layout
layout:
	@mkdir -p $(BUILD)/share/textura
	@ln -sfn ../../../palettes $(BUILD)/share/textura/palettes
	@ln -sfn ../../../patterns $(BUILD)/share/textura/patterns
	@ln -sfn ../../../share/proto $(BUILD)/share/textura/proto
	@printf 'CC = %s\nCXX = %s\nSANITIZE = %s\nOPT = %s\n' '$(CC)' '$(CXX)' '$(SANITIZE)' '$(OPT)' \
	    >$(BUILD)/config.mk

# libtex exports only what its installed headers declare (base/api.h): everything else in
# it is hidden, FLANN's templates and libstdc++'s included.
$(BUILD)/obj/libtex/%.o: ALL_CFLAGS += -fvisibility=hidden
$(BUILD)/obj/libtex/%.o: ALL_CXXFLAGS += -fvisibility=hidden -fvisibility-inlines-hidden

$(BUILD)/obj/%.o: %.c | $(DEPS_FIRST)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(ALL_CFLAGS) -MMD -MP -c -o $@ $<

$(BUILD)/obj/%.o: %.cpp | $(DEPS_FIRST)
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) $(ALL_CXXFLAGS) -ffp-contract=off $(SAN) -MMD -MP -c -o $@ $<

# The renderer's work at a hit is many small steps: -O3's inlining and unrolling take 6-7 %
# off t_apply's CPU on the tests/bench/render scenes, to the same bytes.  The rest of
# libtex stays at OPT; a build at another OPT (-O1 under ASan) keeps it here too.
#
# The renderer's files call each other at every hit and every ray (lights, the BVH,
# shapes, textures): gcc's link-time optimisation inlines across them in t_apply.  Fat
# objects: every other program links their machine code as it is.  Not under a sanitizer
# or clang (whose LTO objects are not fat), nor at another OPT.  (GNU_CC asked the compiler once.)
# Every other link says -fno-lto: else gcc's linker plugin claims the fat objects and
# optimises them again (a unit test's link took 4 s, against 0.25).
RENDER_LTO := $(if $(and $(filter -O2,$(OPT)),$(GNU_CC),$(if $(SANITIZE),,1)),-flto=auto -ffat-lto-objects)
$(BUILD)/obj/libtex/render/%.o: ALL_CFLAGS += $(if $(filter -O2,$(OPT)),-O3) $(RENDER_LTO)
LINK_LTO = $(if $(RENDER_LTO),-fno-lto)
$(BUILD)/bin/t_apply: LINK_LTO = $(if $(RENDER_LTO),-flto=auto -O3)

# the tools alone, without the shared library and the bridges
tools: $(TOOLS) layout

$(STATIC): $(LIB_OBJ)
	@mkdir -p $(@D)
	rm -f $@
	ar rcs $@ $^

# libtex.so's symbols: the tex_ names its objects leave visible (base/api.h); the C++
# run-time's template instances and OpenMP's named critical sections stay inside.
$(SHARED): $(LIB_OBJ)
	@mkdir -p $(@D)
	printf '{ global: tex_*; local: *; };\n' >$(BUILD)/lib/libtex.sym
	$(CC) -shared -Wl,-soname,libtex.so.0 -Wl,--version-script=$(BUILD)/lib/libtex.sym $(LDFLAGS) \
	    $(LINK_LTO) -o $@ $^ $(LDLIBS)
	ln -sf libtex.so.0 $(BUILD)/lib/libtex.so

$(BRIDGE): libtex/io/oiio_bridge.cpp libtex/io/oiio_bridge.h | $(DEPS_FIRST)
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) $(ALL_CXXFLAGS) -shared -fvisibility=hidden -o $@ $< \
	    $$(pkg-config --cflags --libs OpenImageIO)

$(BUILD)/lib/textura/textura-%.so: libtex/io/%_bridge.c libtex/io/codec_bridge.h | $(DEPS_FIRST)
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(filter-out -fopenmp,$(ALL_CFLAGS)) -shared -fvisibility=hidden -o $@ $< \
	    $(CODEC_LIBS_$*)

# pkg-config file for a prefix: $(call pc,PREFIX,LIBDIR).  Headers are
# included as <textura/textura.h>; Libs carries an rpath so that a program
# runs from a prefix outside the loader's path without LD_LIBRARY_PATH.
pc = printf 'prefix=%s\nlibdir=%s\nincludedir=$${prefix}/include\n\nName: textura\nDescription: Textura texture synthesis library (libtex)\nVersion: %s\nCflags: -I$${includedir} -fopenmp\nLibs: -L$${libdir} -Wl,-rpath,$${libdir} -ltex\nLibs.private: %s -fopenmp\n' '$(1)' '$(2)' '$(VERSION)' '$(LDLIBS)'

$(PCFILE): Makefile
	@mkdir -p $(@D)
	$(call pc,$(PREFIX),$(LIBDIR)) > $@

# t_proto serves the editor over HTTP with libmicrohttpd; its parts other than main are
# in tools/proto/ (proto.h), linked into it alone (they are not tools).
PROTO_OBJ = $(patsubst %.c,$(BUILD)/obj/%.o,$(wildcard tools/proto/*.c))
$(BUILD)/bin/t_proto: PROG_LDLIBS += -lmicrohttpd
$(BUILD)/bin/t_proto: PROG_OBJ = $(PROTO_OBJ)
$(BUILD)/bin/t_proto: $(PROTO_OBJ)

$(BUILD)/bin/%: $(BUILD)/obj/tools/%.o $(OMP_ENV) $(STATIC)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) $(LINK_LTO) $(PROG_LDFLAGS) -o $@ $< $(PROG_OBJ) $(OMP_ENV) $(STATIC) $(PROG_LDLIBS)

.PRECIOUS: $(BUILD)/obj/%.o
# each unit test's program from its object, wherever its layer's folder is
$(foreach t,$(UNIT_SRC),$(eval $(BUILD)/tests/$(basename $(notdir $(t))): $(BUILD)/obj/$(t:.c=.o)))
$(UNITS): $(STATIC)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) $(LINK_LTO) -o $@ $(filter %.o,$^) $(STATIC) $(PROG_LDLIBS)

$(BUILD)/obj/tests/%.o: CPPFLAGS += -Itests

check: all $(UNITS)

deps:
	apt-get update -qq
	DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(DEBS)

demo: all
	$(BUILD)/bin/t_noise -s 512 --frequency 12 -S 7 | $(BUILD)/bin/t_apply -o demo.png patterns/still_life.scene
	@echo "wrote demo.png"

# make test: the suite as built and again built with AddressSanitizer and UBSan, and
# tests/house/compilers.sh on a clang build (maps must not depend on the compiler).  The three
# trees build at once, one job per core in all; tests/run runs the files concurrently.
# make test-clang runs the whole suite on the clang build (CI runs it after make test).
# The sanitizer and clang trees keep line tables only (-g1): reports and backtraces
# name every frame's line, and the compilers spend a fifth to a third less time on
# them.  compilers.sh needs only clang's tools.
ASAN_TREE  = BUILD=build-asan SANITIZE=1 OPT=-O1 CFLAGS='-O1 -g1' CXXFLAGS='-O1 -g1'
CLANG_TREE = BUILD=build-clang CC=clang CXX=clang++ CFLAGS='-O2 -g1' CXXFLAGS='-O2 -g1'
.PHONY: check-plain check-asan check-clang check-clang-units tools
check-plain:
	+$(MAKE) check
check-asan:
	+$(MAKE) check $(ASAN_TREE)
check-clang:
	+$(MAKE) tools $(CLANG_TREE)
check-clang-units:
	+$(MAKE) check $(CLANG_TREE)

test: check-plain check-asan check-clang
	tests/run build build-asan build-clang:compilers.sh

test-plain: check
	tests/run build

test-clang: check-clang-units
	tests/run build-clang

# The unit tests under ThreadSanitizer, built with clang and LLVM's OpenMP
# runtime; Archer (libarcher) makes TSan see OpenMP's synchronisation.
TSAN_BUILD ?= build-tsan
ARCHER ?= $(firstword $(wildcard /usr/lib/llvm-*/lib/libarcher.so))
tsan:
	$(MAKE) check BUILD=$(TSAN_BUILD) CC=clang CXX=clang++ SANITIZE=1 OPT=-O1 \
		SANFLAGS="-fsanitize=thread -fno-omit-frame-pointer"
	@fail=0; for t in $(TSAN_BUILD)/tests/test_*; do \
		OMP_NUM_THREADS=2 OMP_TOOL_LIBRARIES=$(ARCHER) TEXTURA_TOP=$(CURDIR) \
		TSAN_OPTIONS="halt_on_error=1 suppressions=$(CURDIR)/tests/tsan.supp" \
		$$t >$$t.log 2>&1 && echo "ok - $$t under TSan" || { echo "not ok - $$t: see $$t.log"; fail=1; }; \
	done; exit $$fail

bench: all
	tests/bench/run $(BUILD)

man: all
	tests/mkman $(BUILD)/bin

# the thesis's figures with their captions (doc/figures/figures.md), and a gallery of every
# primitive, palette, filter and operator (gallery/index.html, gallery/gallery.png)
figures: all
	PATH="$(CURDIR)/$(BUILD)/bin:$$PATH" patterns/figures.sh -o doc/figures
	PATH="$(CURDIR)/$(BUILD)/bin:$$PATH" FIGURES=photo_4.1 patterns/figures.sh -o $(BUILD)/photo -s 800
	cp $(BUILD)/photo/fig_photo_4.1.png doc/images/photo_4.1.png
	$(BUILD)/bin/t_apply patterns/resolution.scene -s 720x405 -q -o doc/images/resolution.png
	$(BUILD)/bin/t_fractal --mode fbm -s 1024x512 -f 6 | $(BUILD)/bin/t_palette sky | \
	    $(BUILD)/bin/t_apply patterns/mirror_ball.scene -s 720x480 -q -o doc/images/mirror_ball.png

gallery: all
	PATH="$(CURDIR)/$(BUILD)/bin:$$PATH" patterns/gallery.sh -o gallery

fuzz:
	$(MAKE) -C tests/fuzz BUILD=$(abspath $(BUILD))/fuzz

fuzz-libs:
	$(MAKE) -C tests/fuzz libs BUILD=$(abspath $(BUILD))/fuzz

# CI (.ci/run, after make test): each fuzz target 20 s over its seed corpus, 15 targets two
# at a time: under 3 min
fuzz-smoke: fuzz
	tests/fuzz/smoke.sh $(abspath $(BUILD))/fuzz 20

# The installed libtex.a holds machine code alone: the LTO bytecode of the renderer's
# objects (t_apply's) would have gcc optimise them again in every program linked with
# it (4 s a link).
#
# A tree built for one prefix installs at another without being rebuilt (a
# distribution builds, then installs with PREFIX and DESTDIR): the objects
# do not depend on PREFIX, and the installed tree finds its parts relative
# to itself at run time (libtex/base/paths.h).
INSTALLED_TOOLS = $(TOOLS:$(BUILD)/bin/%=%)
install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(LIBDIR)/textura $(DESTDIR)$(LIBDIR)/pkgconfig \
	    $(addprefix $(DESTDIR)$(PREFIX)/include/textura/,$(LAYERS)) $(DESTDIR)$(PREFIX)/share/man/man1 \
	    $(DESTDIR)$(PREFIX)/share/man/man3 $(DESTDIR)$(PREFIX)/share/man/man5 \
	    $(DESTDIR)$(DATADIR)/palettes $(DESTDIR)$(DATADIR)/patterns $(DESTDIR)$(DATADIR)/proto
	install -m 755 $(TOOLS) $(DESTDIR)$(PREFIX)/bin
	objcopy -R '.gnu.lto_*' -R '.gnu.debuglto_*' $(STATIC) $(DESTDIR)$(LIBDIR)/libtex.a
	chmod 644 $(DESTDIR)$(LIBDIR)/libtex.a
	install -m 755 $(SHARED) $(DESTDIR)$(LIBDIR)
	ln -sf libtex.so.0 $(DESTDIR)$(LIBDIR)/libtex.so
	install -m 755 $(BRIDGE) $(CODEC_BRIDGES) $(DESTDIR)$(LIBDIR)/textura
	$(call pc,$(PREFIX),$(LIBDIR)) > $(DESTDIR)$(LIBDIR)/pkgconfig/textura.pc
	install -m 644 libtex/textura.h $(DESTDIR)$(PREFIX)/include/textura
	for h in $(HEADERS); do install -m 644 $$h $(DESTDIR)$(PREFIX)/include/textura/$${h#libtex/}; done
	install -m 644 $(wildcard man/man1/*.1) $(DESTDIR)$(PREFIX)/share/man/man1
	install -m 644 $(wildcard man/man3/*.3) $(DESTDIR)$(PREFIX)/share/man/man3
	install -m 644 $(wildcard man/man5/*.5) $(DESTDIR)$(PREFIX)/share/man/man5
	cp -R palettes/. $(DESTDIR)$(DATADIR)/palettes
	cp -R patterns/. $(DESTDIR)$(DATADIR)/patterns
	install -m 644 share/proto/index.html $(DESTDIR)$(DATADIR)/proto

uninstall:
	rm -f $(addprefix $(DESTDIR)$(PREFIX)/bin/,$(INSTALLED_TOOLS))
	rm -f $(DESTDIR)$(LIBDIR)/libtex.a $(DESTDIR)$(LIBDIR)/libtex.so.0 $(DESTDIR)$(LIBDIR)/libtex.so
	rm -f $(DESTDIR)$(LIBDIR)/pkgconfig/textura.pc
	rm -rf $(DESTDIR)$(LIBDIR)/textura $(DESTDIR)$(PREFIX)/include/textura $(DESTDIR)$(DATADIR)
	for f in $(notdir $(wildcard man/man1/*.1)); do rm -f $(DESTDIR)$(PREFIX)/share/man/man1/$$f; done
	for f in $(notdir $(wildcard man/man3/*.3)); do rm -f $(DESTDIR)$(PREFIX)/share/man/man3/$$f; done
	for f in $(notdir $(wildcard man/man5/*.5)); do rm -f $(DESTDIR)$(PREFIX)/share/man/man5/$$f; done

clean:
	rm -rf build build-asan build-clang build-tsan demo.png gallery

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)
