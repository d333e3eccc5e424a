# upkie-rl: the two-command quick start is `make train` and `make test`.
BUILD_DIR ?= build
SANITIZE_DIR ?= build-sanitize
TSAN_DIR ?= build-tsan
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=
# Debian's interpreter: it has python3-torch (SB3, TorchScript checks); the extension
# module is built for it.
PYTHON ?= /usr/bin/python3

.PHONY: all deps configure build test test-cpp test-python test-debian13 test-docs docs typecheck-python wheel test-wheel bench train train-mujoco train-robust train-velocity train-velocity-robust sim2real-demo train-scratch sanitize sanitize-thread fuzz fuzz-long fuzz-python format tidy clean pi

all: build

deps:
	PYTHON=$(PYTHON) bash scripts/install-deps.sh

$(BUILD_DIR)/build.ninja:
	cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=$(PYTHON) $(CMAKE_FLAGS)

configure: $(BUILD_DIR)/build.ninja

build: deps configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

test-cpp:
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The Python tests run twice: against the oldest Gymnasium the package supports (1.0.0, in
# Debian's interpreter, with SB3) and the newest pyproject.toml allows (the venv of
# scripts/install-deps.sh), after mypy checks the package, its stubs and their use.
GYMNASIUM_NEWEST_PYTHON ?= .venv-gymnasium-newest/bin/python
PYTEST_ENV = UPKIE_RL_BUILD_DIR=$(abspath $(BUILD_DIR)) PYTHONPATH=$(abspath $(BUILD_DIR))/python

# The docs' console examples (test_doc_examples.py) run the CLI and Debian's interpreter, and
# the docs site (test_docs_site.py) is built by its own venv, whichever Python runs pytest:
# they run once, in the first pass.
test-python: typecheck-python
	$(PYTEST_ENV) $(PYTHON) -m pytest -q python/tests
	$(PYTEST_ENV) $(GYMNASIUM_NEWEST_PYTHON) -m pytest -q python/tests \
	  --ignore=python/tests/test_doc_examples.py --ignore=python/tests/test_docs_site.py

typecheck-python:
	$(PYTEST_ENV) $(PYTHON) -m mypy
	MYPYPATH=$(abspath $(BUILD_DIR))/python $(PYTEST_ENV) $(PYTHON) -m mypy.stubtest upkie_rl._core --allowlist python/stubtest-allowlist.txt

test: build
	$(MAKE) docs
	$(MAKE) test-cpp
	$(MAKE) test-python
	WHEEL_TEST_SB3=$(or $(WHEEL_TEST_SB3),1) $(MAKE) test-wheel

# The C++ and Python tests of a clean clone of HEAD inside a Debian 13 (trixie) chroot made
# by debootstrap (scripts/test-debian13.sh; root, DEBIAN13_ROOT=/var/tmp/upkie-rl-trixie by
# default, reused at the next run). Not part of `make test`: its first run installs Debian 13's
# packages and builds everything from nothing.
test-debian13:
	JOBS=$(or $(DEBIAN13_JOBS),2) bash scripts/test-debian13.sh

# Every console example of README.md and docs/, the slow ones (trainings, grids) too, run and
# compared with the text (python/tests/doc_examples.py says how); `make test` runs the quick ones.
test-docs:
	$(PYTEST_ENV) UPKIE_RL_DOCS_SLOW=1 $(PYTHON) -m pytest -q python/tests/test_doc_examples.py

# The docs site: docs/ built by MkDocs (Material theme, mkdocstrings for the API page) in
# strict mode into $(BUILD_DIR)/docs; the packages go to a venv of their own (DOCS_VENV).
DOCS_VENV ?= .venv-docs
docs:
	DOCS_VENV=$(DOCS_VENV) PYTHON=$(PYTHON) bash scripts/install-docs-deps.sh
	NO_MKDOCS_2_WARNING=1 $(DOCS_VENV)/bin/mkdocs build --strict --quiet \
	  --site-dir $(abspath $(BUILD_DIR))/docs
	@echo "docs site: $(BUILD_DIR)/docs/index.html"

# Python wheels (docs/wheels.md): manylinux wheels of the upkie_rl package for CPython
# 3.10-3.13 in dist/, built by scikit-build-core and repaired by auditwheel
# (scripts/wheels/build.sh; the interpreters: scripts/wheels/python-for.sh).
WHEEL_PYTHONS ?= 3.10 3.11 3.12 3.13
wheel:
	JOBS=$(JOBS) bash scripts/wheels/build.sh $(WHEEL_PYTHONS)

# The cp312 wheel, built (again, incrementally) then installed into a bare pyenv 3.12 venv
# and tested from outside the repository (scripts/wheels/test.sh); the last step of `make
# test`, so CI tests a wheel. It needs PyPI (build requirements, the wheel's dependencies) and
# a build tree of its own. WHEEL_TEST_SB3=1 adds SB3 and PyPI's torch (about 3 GB) for the
# training tests, which are skipped without it.
test-wheel:
	JOBS=$(JOBS) bash scripts/wheels/build.sh 3.12
	bash scripts/wheels/test.sh

# Trains the seed's pendulum policy, evaluates the final model on 10 episodes from the
# exact start (the seed's protocol) and 10 from the evaluations' random starts (each summary
# line says which), and draws the training figures. TRAIN_CONFIG and RUN_DIR can be overridden.
TRAIN_CONFIG ?= configs/pendulum.yaml
TRAIN_ENV ?= Upkie-Bullet-Pendulum
TRAIN_SET ?=
ifndef RUN_DIR
RUN_DIR := runs/pendulum-$(shell date +%Y%m%d-%H%M%S)
endif

train: build
	$(BUILD_DIR)/upkie-rl train --config $(TRAIN_CONFIG) $(TRAIN_SET) --run-dir $(RUN_DIR)
	@model=$$(ls -t $(RUN_DIR)/model_*.ckpt | head -n 1); \
	  echo "evaluating $$model on 10 episodes from the exact start, then 10 from random starts"; \
	  { $(BUILD_DIR)/upkie-rl rollout --env $(TRAIN_ENV) --model $$model --episodes 10 --exact-start && \
	    $(BUILD_DIR)/upkie-rl rollout --env $(TRAIN_ENV) --model $$model --episodes 10; } \
	    > $(RUN_DIR)/evaluation.txt 2>&1; status=$$?; cat $(RUN_DIR)/evaluation.txt; exit $$status
	$(BUILD_DIR)/upkie-rl plot $(RUN_DIR)
	@echo "run directory: $(RUN_DIR) (config.yaml, progress.csv, TensorBoard events," \
	  "checkpoints/, model_*.ckpt and model_*.pt, evaluation.txt, loss.png, kl.png, return.png)"
	@echo "TensorBoard: tensorboard --logdir $(RUN_DIR)"

# The same job on MuJoCo: the seed's configuration on Upkie-MuJoCo-Pendulum.
train-mujoco:
	$(MAKE) train TRAIN_ENV=Upkie-MuJoCo-Pendulum TRAIN_SET="--set env.id=Upkie-MuJoCo-Pendulum" \
	  RUN_DIR=runs/pendulum-mujoco-$(shell date +%Y%m%d-%H%M%S)

# The robust pendulum (docs/robustness.md), then its success rates beside PD and LQR.
train-robust:
	$(MAKE) train TRAIN_CONFIG=configs/pendulum_robust.yaml TRAIN_ENV=Upkie-MuJoCo-Pendulum \
	  RUN_DIR=runs/pendulum-robust-$(shell date +%Y%m%d-%H%M%S)
	@run=$$(ls -td runs/pendulum-robust-* | head -n 1); model=$$(ls -t $$run/model_*.ckpt | head -n 1); \
	  $(BUILD_DIR)/upkie-rl evaluate --env Upkie-MuJoCo-Pendulum --controller pd=linear:10,1,0,0.1 \
	    --controller lqr --model robust=$$model --grid push=0:40:5,mass=0.7:1.3:0.1 \
	    --episodes 10 --output $$run/robustness

# Drive anywhere (docs/environments.md, "Velocity"): trains configs/velocity.yaml (MuJoCo, a quarter on Bullet),
# then compares the policy with the classical balancer (lqr) on 20 episodes of 20 s with
# random commands and pushes up to 20 N on MuJoCo, the policy on Bullet (sim-to-sim), and
# draws commanded against measured velocities, with a video and a still of it, then runs the
# reality suite (configs/suites/reality.yaml, docs/reality.md) on the policy and the baseline.
VELOCITY_EVAL = --episodes 20 --seed 1000 --max-steps 1000 --env-option max_episode_steps=1000 \
  --env-option push_force=20 --env-option push_duration=0.2 --env-option push_interval=3 \
  --env-option push_direction=any --env-option height_command=false --env-option leg_action_scale=0.5
# A velocity run's evaluations: $(1) its directory, $(2) the policy's name in the tables,
# $(3) the evaluations' options, $(4) the stem of the outputs, $(5) the scripted commands.
# 20 episodes on MuJoCo beside the classical baseline, the policy alone on Bullet
# (sim-to-sim), then the scripted commands plotted and filmed, with a still at 10 s.
define evaluate_velocity_run
	@run=$(1); model=$$(ls -t $$run/model_*.ckpt | head -n 1); \
	  $(BUILD_DIR)/upkie-rl evaluate --env Upkie-MuJoCo-Velocity --model $(2)=$$model \
	    --controller lqr $(3) --output $$run/$(4)-mujoco && \
	  $(BUILD_DIR)/upkie-rl evaluate --env Upkie-Bullet-Velocity --model $(2)=$$model \
	    $(3) --output $$run/$(4)-bullet && \
	  $(BUILD_DIR)/upkie-rl rollout --env Upkie-MuJoCo-Velocity --model $$model \
	    --commands $(5) --max-steps 1000 --env-option max_episode_steps=1000 \
	    --plot $$run/$(4) --json --video $$run/$(4).mp4 && \
	  ffmpeg -loglevel error -y -ss 10 -i $$run/$(4).mp4 -frames:v 1 $$run/$(4)_still.png && \
	  echo "wrote $$run/$(4).mp4 and $$run/$(4)_still.png"
endef

train-velocity: VELOCITY_RUN := runs/velocity-$(shell date +%Y%m%d-%H%M%S)
train-velocity:
	$(MAKE) train TRAIN_CONFIG=configs/velocity.yaml TRAIN_ENV=Upkie-MuJoCo-Velocity \
	  RUN_DIR=$(VELOCITY_RUN)
	$(call evaluate_velocity_run,$(VELOCITY_RUN),policy,$(VELOCITY_EVAL),velocity,configs/velocity_commands.csv)
	@model=$$(ls -t $(VELOCITY_RUN)/model_*.ckpt | head -n 1); \
	  $(BUILD_DIR)/upkie-rl evaluate --suite reality --model policy=$$model --controller lqr \
	    --output $(VELOCITY_RUN)/reality-suite

# The loop from a robot's log back to a better policy (docs/identify.md): a Bullet spine hides
# a payload's place, a slippery floor and late actuation; the runner records 60 s on it;
# identify fits them on MuJoCo; the velocity policy is retrained with them; both policies are
# evaluated on the hidden reality, side by side (about 15 minutes on 2 cores).
sim2real-demo: build
	BUILD_DIR=$(BUILD_DIR) scripts/sim2real-demo.sh

# The whole robot from scratch (configs/velocity_scratch.yaml, no classical controller
# underneath): trains, evaluates beside the classical baseline on MuJoCo and alone on Bullet at
# the reference 1 ms (sim-to-sim), plots and films the scripted commands.
# The built-in baseline takes only these options (a model carries the task options it was
# trained with): the yaw ramp of configs/velocity_scratch.yaml is repeated here so that the
# two follow the same commands.
SCRATCH_YAW_RAMP = --env-option command_max_yaw_acceleration=10
SCRATCH_EVAL = --episodes 20 --seed 1000 --max-steps 1000 --env-option max_episode_steps=1000 \
  $(SCRATCH_YAW_RAMP)
train-scratch: SCRATCH_RUN := runs/velocity-scratch-$(shell date +%Y%m%d-%H%M%S)
train-scratch:
	$(MAKE) train TRAIN_CONFIG=configs/velocity_scratch.yaml TRAIN_ENV=Upkie-MuJoCo-Velocity \
	  RUN_DIR=$(SCRATCH_RUN)
	$(call evaluate_velocity_run,$(SCRATCH_RUN),scratch,$(SCRATCH_EVAL),scratch,configs/velocity_height_commands.csv)

# The whole robot from scratch, trained for the reality suite's floors
# (configs/velocity_robust.yaml: velocity_scratch.yaml with pushes, a drawn delay, slopes,
# payloads and weaker motors in training, and the last three observations as input): trains,
# evaluates and films as train-scratch does, then runs the reality suite on the policy beside
# the baseline, standing (the shipped suite, every height command at the standing height) and
# crouching (random height commands), both with the yaw ramp the policy trains with.
ROBUST_SUITE = --env-option height_command=true --env-option leg_action_about_crouch=true \
  $(SCRATCH_YAW_RAMP)
train-velocity-robust: ROBUST_RUN := runs/velocity-robust-$(shell date +%Y%m%d-%H%M%S)
train-velocity-robust:
	$(MAKE) train TRAIN_CONFIG=configs/velocity_robust.yaml TRAIN_ENV=Upkie-MuJoCo-Velocity \
	  RUN_DIR=$(ROBUST_RUN)
	$(call evaluate_velocity_run,$(ROBUST_RUN),robust,$(SCRATCH_EVAL),robust,configs/velocity_height_commands.csv)
	@model=$$(ls -t $(ROBUST_RUN)/model_*.ckpt | head -n 1); \
	  $(BUILD_DIR)/upkie-rl evaluate --suite reality --model policy=$$model --controller lqr \
	    $(ROBUST_SUITE) --env-option min_height_command=0.557 --output $(ROBUST_RUN)/reality-suite && \
	  $(BUILD_DIR)/upkie-rl evaluate --suite reality --model policy=$$model --controller lqr \
	    $(ROBUST_SUITE) --output $(ROBUST_RUN)/reality-suite-crouching

bench: build
	for program in $(BUILD_DIR)/bench/*_bench; do $$program --benchmark_min_time=1; done
	PYTHONPATH=$(abspath $(BUILD_DIR))/python $(PYTHON) bench/python/python_step_bench.py \
	  --cli $(BUILD_DIR)/upkie-rl

sanitize: deps
	cmake -S . -B $(SANITIZE_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUPKIE_RL_SANITIZE=ON -DUPKIE_RL_BUILD_BENCH=OFF -DUPKIE_RL_BUILD_PYTHON=OFF -DPython_EXECUTABLE=$(PYTHON)
	cmake --build $(SANITIZE_DIR) -j $(JOBS)
	cd $(SANITIZE_DIR) && ctest --output-on-failure -j $(JOBS)

sanitize-thread: deps
	cmake -S . -B $(TSAN_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUPKIE_RL_SANITIZE_THREAD=ON -DUPKIE_RL_BUILD_BENCH=OFF -DUPKIE_RL_BUILD_PYTHON=OFF -DPython_EXECUTABLE=$(PYTHON)
	cmake --build $(TSAN_DIR) -j $(JOBS)
	# Without the Gloo collectives (Communicator, DistributedTrain, RankAgreement): libtorch
	# and libgloo are not built with TSan, which then reports their own threads' handovers (a
	# work's condition variable notified while its waiter frees it, tensors sent by Gloo's I/O
	# thread, mutexes unlocked from another thread; RankAgreement's broadcast gave the first). They run in `make test` and `make sanitize` (ASan).
	# tests/tsan_suppressions.txt: the other uninstrumented libraries TSan misreads (Mesa).
	cd $(TSAN_DIR) && TSAN_OPTIONS="halt_on_error=1 suppressions=$(abspath tests/tsan_suppressions.txt)" \
	  ctest --output-on-failure -j $(JOBS) \
	  -E '^(Communicator|DistributedTrain|RankAgreement)\.'

# libFuzzer + ASan on the spine's message decoding, server cycle and shared-memory segment,
# the checkpoint gate past the CRC, record files, the viewer's messages, environment
# options and the training configuration with --set: FUZZ_RUNS inputs each, or FUZZ_SECONDS
# each when set (`make fuzz-long`: an hour each); FUZZ_TARGETS names some (all by
# default). The targets, their corpora and maximum input lengths are declared once, in
# fuzz/CMakeLists.txt, which lists them in $(FUZZ_DIR)/fuzz/targets.txt. The corpora also
# run as ctests of every ordinary build (FuzzRegression.*), and a few seconds of mutations
# per target too (FuzzBounded.*, GCC's objects on the same libFuzzer).
FUZZ_DIR ?= build-fuzz
FUZZ_RUNS ?= 1000000
FUZZ_SECONDS ?=
FUZZ_LIMIT = $(if $(FUZZ_SECONDS),-max_total_time=$(FUZZ_SECONDS),-runs=$(FUZZ_RUNS))
FUZZ_TARGETS ?=
# A fuzzer's stdout (the spine's error log, one line per refused message) is dropped;
# libFuzzer reports on stderr.
fuzz:
	UPKIE_RL_FUZZ=1 bash scripts/install-deps.sh
	# The release's clang, which install-deps.sh installs (14 on Debian 12, 19 on Debian 13).
	cmake -S . -B $(FUZZ_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_COMPILER=$$(ls /usr/bin/clang++-[0-9]* | sort -V | tail -n 1) -DUPKIE_RL_BUILD_FUZZ=ON \
	  -DUPKIE_RL_BUILD_TESTS=OFF -DUPKIE_RL_BUILD_BENCH=OFF -DUPKIE_RL_BUILD_PYTHON=OFF \
	  -DPython_EXECUTABLE=$(PYTHON)
	cmake --build $(FUZZ_DIR) -j $(JOBS) --target $(or $(FUZZ_TARGETS),fuzzers)
	set -e; while read -r name corpus max_len; do \
	  case " $(or $(FUZZ_TARGETS),$$name) " in *" $$name "*) ;; *) continue ;; esac; \
	  mkdir -p $(FUZZ_DIR)/corpus_$$name; \
	  echo "fuzzing $$name"; \
	  $(FUZZ_DIR)/fuzz/$$name $(FUZZ_LIMIT) -max_len=$$max_len -timeout=10 -rss_limit_mb=4096 \
	    -print_final_stats=1 $(FUZZ_DIR)/corpus_$$name fuzz/$$corpus >/dev/null; \
	done < $(FUZZ_DIR)/fuzz/targets.txt

fuzz-long:
	$(MAKE) fuzz FUZZ_SECONDS=3600

# Hypothesis on the Python package (python/tests/fuzz_inputs.py): the SB3 zip and
# VecNormalize readers, the model readers, the registry's and make functions, a policy's
# inputs and the sb3_convert command, FUZZ_PYTHON_TOTAL inputs over the targets (shared by
# their cost, fuzz_inputs.SHARES); `make test-python` runs each on a few hundred.
FUZZ_PYTHON_TOTAL ?= 1000000
FUZZ_PYTHON_TARGETS ?=
fuzz-python:
	$(PYTEST_ENV) $(PYTHON) python/tests/fuzz_inputs.py --total $(FUZZ_PYTHON_TOTAL) \
	  $(if $(FUZZ_PYTHON_TARGETS),--targets $(FUZZ_PYTHON_TARGETS))

# The robot's bundle: upkie-rl-agent cross-compiled for aarch64 (Raspberry Pi 4), its arm64
# libraries, a policy (PI_POLICY), the URDF, a run script and a README, in $(PI_DIR)/bundle.
PI_DIR ?= build-pi
PI_POLICY ?= tests/data/policies/pendulum_bullet_seed0.ckpt
pi: deps
	cmake -S . -B $(PI_DIR)/cmake -G Ninja -DCMAKE_BUILD_TYPE=Release \
	  -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DUPKIE_RL_AGENT_ONLY=ON
	cmake --build $(PI_DIR)/cmake -j $(JOBS)
	bash scripts/pi/make-bundle.sh $(PI_DIR)/cmake/upkie-rl-agent $(PI_POLICY) $(PI_DIR)/bundle

format:
	find src tests bench -name '*.hpp' -o -name '*.cpp' | xargs clang-format -i

tidy: configure
	find src -name '*.cpp' | xargs -P $(JOBS) -n 4 clang-tidy -p $(BUILD_DIR) --quiet 2>/dev/null

clean:
	rm -rf $(BUILD_DIR) $(SANITIZE_DIR) $(TSAN_DIR) $(PI_DIR)
