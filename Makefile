# make demo: install what is missing, build lagmb, run the seed pendulum.
# make test: the same set-up, then the test suite.
# make test-asan: the test suite under AddressSanitizer and UBSan.
# make docs: the documentation site into build/docs/html (warnings are errors).
# make wheel: one self-contained wheel (SUNDIALS and KLU inside) in build/wheel/dist.
# make clean-room: that wheel installed offline into a bare Debian, and checked there.
PYTHON ?= $(shell scripts/python.sh)
SOURCES := $(shell find cpp python -type f -not -name '*.pyc') CMakeLists.txt pyproject.toml
STAMP := build/.installed-$(subst /,_,$(PYTHON))

.PHONY: demo test test-slow test-fuzz test-asan bench docs setup clean wheel clean-room

demo: $(STAMP)
	$(PYTHON) -m lagmb demo --plot out/seed_pendulum.png

test: $(STAMP)
	$(PYTHON) -m pytest -q

test-slow: $(STAMP)
	$(PYTHON) -m pytest -q -m slow

test-fuzz: $(STAMP)
	$(PYTHON) -m pytest -q -m fuzz

# the suite against a build with AddressSanitizer and UBSan (build/asan); it
# does not install anything, so it does not depend on $(STAMP)
test-asan:
	scripts/test-asan.sh $(PYTHON)

bench: $(STAMP)
	$(PYTHON) bench/performance/chain.py

# from scratch, so the gallery runs every example against the code as it is
# (tests/tools/test_docs.py builds the same pages, reusing the gallery's outputs)
docs: $(STAMP)
	rm -rf build/docs docs/gallery docs/generated
	$(PYTHON) -m sphinx -W --keep-going -b html docs build/docs/html
	@echo "docs: build/docs/html/index.html"

# (does not install lagmb; it builds in build/wheel, apart from make's build)
wheel:
	scripts/wheel.sh $(PYTHON)

clean-room: wheel
	scripts/clean-room.sh build/wheel/dist

setup: $(STAMP)

$(STAMP): $(SOURCES) scripts/setup.sh
	scripts/setup.sh $(PYTHON)
	@mkdir -p build && touch $@

clean:
	rm -rf build out
