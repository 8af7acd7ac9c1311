# tribofx: `make demo` sets everything up and runs the main demo; `make test` runs the tests.
VENV     ?= .venv
PY       := $(VENV)/bin/python
MPIEXEC  := $(VENV)/bin/mpiexec
export UCX_TLS ?= self,sm,tcp
export OMP_NUM_THREADS ?= 1
STAMP    := $(VENV)/.tribofx-installed
SOURCES  := pyproject.toml constraints.txt $(wildcard cpp_kernels/CMakeLists.txt cpp_kernels/src/*)

.PHONY: setup demo test test-slow lint bench docs-results clean lock

setup: $(STAMP)

$(STAMP): $(SOURCES) .ci/setup.sh
	VENV=$(VENV) bash .ci/setup.sh
	touch $@

demo: setup
	$(PY) demos/demo_tour.py --out results

# the suite on the 2 cores (pytest-xdist, one test file per worker so that a file's
# module fixtures are built once), except the tests that start mpiexec themselves,
# which run next, alone; then the tests marked `mpi` again on 2 processes
XDIST    := -n 2 --dist loadfile
test: setup
	$(PY) -m pytest -q $(XDIST) -m "not mpiexec" --durations=15 $(PYTEST_ARGS)
	$(PY) -m pytest -q -m mpiexec $(PYTEST_ARGS)
	$(MPIEXEC) -n 2 $(PY) -m pytest -q -m mpi -p no:cacheprovider $(PYTEST_ARGS)

# the tests marked slow (the full versions of checks the default run makes in a cheap
# form), in the same three passes (about 24 min on 2 cores; .ci/run runs it after `make test`).
# A few long tests sit in a few files, so the serial pass hands out tests, not files,
# to the two workers
test-slow: setup
	$(PY) -m pytest -q -n 2 --dist load -m "slow and not mpiexec" --runslow --durations=15 $(PYTEST_ARGS)
	$(PY) -m pytest -q -m "slow and mpiexec" --runslow $(PYTEST_ARGS); \
	  status=$$?; [ $$status -eq 0 ] || [ $$status -eq 5 ]   # 5: none selected (none today)
	$(MPIEXEC) -n 2 $(PY) -m pytest -q -m "slow and mpi" -p no:cacheprovider --runslow $(PYTEST_ARGS)

lint: setup
	$(VENV)/bin/ruff check .
	$(VENV)/bin/mypy

# the generated parts of docs/cases/<case>.md: parameter tables and the results of each
# page's command, stamped with the commit and the machine (a few minutes on 2 cores)
docs-results: setup
	$(PY) benchmarks/docs_results.py

# the full Fig. 4 wear study (benchmarks/bench_wear_study.py) takes hours, and the
# direct/iterative size sweep (benchmarks/bench_solvers.py --ranks2) about an hour: run them by hand
bench: setup
	$(PY) benchmarks/bench_projection.py
	$(PY) benchmarks/bench_hertz.py
	$(PY) benchmarks/bench_wear.py
	$(PY) benchmarks/bench_ehl.py
	$(PY) benchmarks/bench_ehl_ball.py
	$(PY) benchmarks/bench_wear_ball.py
	$(PY) benchmarks/bench_wear_groove.py
	$(PY) benchmarks/bench_two_body.py

# the newest versions into a fresh venv, frozen into constraints.txt (then run make test)
lock:
	rm -rf .venv-lock
	VENV=.venv-lock UNLOCKED=1 bash .ci/setup.sh
	{ sed -n '/^#/p' constraints.txt; .venv-lock/bin/pip freeze --all --exclude-editable; } \
	  > constraints.txt.new
	mv constraints.txt.new constraints.txt
	rm -rf .venv-lock

clean:
	rm -rf build results $(VENV)
