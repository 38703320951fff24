# Fennel raymarcher. `make run` and `make test` install what is missing first
# (Debian packages, and Fennel from Debian trixie's .deb); see tools/install-deps.sh.

SCENE ?= scenes/seed.fnl
HEADLESS = SDL_VIDEODRIVER=offscreen

.PHONY: deps build run test check bench golden report report-quick dist clean check-states edit-window

deps:
	@bash tools/install-deps.sh

# The app's Fennel compiled to Lua once (build/lua/, see src/boot.lua): LÖVE starts
# without compiling it, and so does each scene worker. A stale or missing file is
# compiled at start as before, so `love .` works without this too, only slower.
build: deps
	@luajit tools/build-lua.lua --quiet

# Without a display the window would open nowhere and the player run unseen forever.
run: build
	@if [ -z "$$DISPLAY$$WAYLAND_DISPLAY$$SDL_VIDEODRIVER" ]; then \
	  echo "make run: no display (DISPLAY and WAYLAND_DISPLAY are unset): run it in a desktop session, or under xvfb-run to try it headless" >&2; \
	  exit 1; fi
	love . $(SCENE)

# The suite also makes a quick accuracy report, whose plots need gnuplot.
test:
	@bash tools/install-deps.sh gnuplot-nox zip xvfb xdotool x11-apps bc
	@luajit tools/build-lua.lua --quiet
	@$(HEADLESS) bash tools/run-tests.sh

# The fast loop while developing: the specs that need no window or GPU, a sample of the
# corpus through the app and 500 fuzz cases (see docs/testing.md). `make test` is the suite.
check: build
	@$(HEADLESS) bash tools/run-tests.sh --check

# Mesa's shader cache off: the compile times it prints are compiles, not cache hits.
bench: build
	$(HEADLESS) MESA_SHADER_CACHE_DISABLE=true love . --bench-report --frames $(or $(FRAMES),5)

# Accuracy against run time for every scene (report/report.md and plots); gnuplot
# draws the plots and is installed for this target only.
report: deps
	@bash tools/install-deps.sh gnuplot-nox
	luajit tools/fnl.lua tools/report.fnl

report-quick: deps
	@bash tools/install-deps.sh gnuplot-nox
	luajit tools/fnl.lua tools/report.fnl --quick

# Under Xvfb: does the player ever show a picture mixing two scene states? (about
# a minute; PLAYER=DIR checks another checkout's player; see README, Tests).
check-states:
	@bash tools/install-deps.sh xvfb xdotool x11-apps bc
	bash tools/check-states.sh $(PLAYER)

# Under Xvfb: the time from saving an edit of each showcase scene to its picture
# (about 5 minutes; PLAYER=DIR times another checkout's player; see docs/testing.md).
edit-window:
	@bash tools/install-deps.sh xvfb xdotool x11-apps bc
	PLAYER=$(or $(PLAYER),.) bash tools/edit-window.sh

golden: deps
	$(HEADLESS) luajit tools/fnl.lua tools/golden.fnl

# dist/fennel-raymarcher.love: plays with `love dist/fennel-raymarcher.love` anywhere LÖVE is.
dist: build
	@bash tools/install-deps.sh zip
	@bash tools/dist.sh

clean:
	rm -rf out test/out dist build
