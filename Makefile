# Fennel raymarcher. `make run` and `make test` install what is missing first
# (Debian packages, and Fennel from Debian trixie's .deb); see tools/install-deps.sh.

SCENE ?= scenes/seed.fnl
HEADLESS = SDL_VIDEODRIVER=offscreen

.PHONY: deps run test bench golden report report-quick clean

deps:
	@bash tools/install-deps.sh

run: deps
	love . $(SCENE)

# The suite also makes a quick accuracy report, whose plots need gnuplot.
test:
	@bash tools/install-deps.sh gnuplot-nox
	@$(HEADLESS) bash tools/run-tests.sh

bench: deps
	$(HEADLESS) love . --bench-report --frames $(or $(FRAMES),5)

# Accuracy against run time for every scene (report/report.md and plots); gnuplot
# draws the plots and is installed for this target only.
report: deps
	@bash tools/install-deps.sh gnuplot-nox
	luajit tools/fnl.lua tools/report.fnl

report-quick: deps
	@bash tools/install-deps.sh gnuplot-nox
	luajit tools/fnl.lua tools/report.fnl --quick

golden: deps
	$(HEADLESS) luajit tools/fnl.lua tools/golden.fnl

clean:
	rm -rf out test/out
