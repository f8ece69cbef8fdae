# ContrACT Studio — top-level entry points. See README.md.
#   make start   install what is missing, build, and serve the IDE + build service on the tutorial
#   make test    install what is missing, build, and run every test (TypeScript, C, browser, sandboxes)
#   make bench   run every benchmark, write bench/results.json
#   make test-node-versions   CLI smoke, a simulation and a real run told by `contract trace`, contract serve, language/codegen tests on Node 22, 24 and 26 (several minutes: not in make test)
#   make pack-cli             the CLI as one self-contained tarball in dist-packages/ (npm install -g it)
#   make test-installed-cli   pack, install into a temp prefix, new/check/build/run outside the repository
.PHONY: setup start test test-ts test-c test-node-versions pack-cli test-installed-cli bench clean

setup:
	bash scripts/setup.sh

# make start PROJECT=path/to/project PORT=7410: another project or port (the tutorial on 7400 by
# default); taken from make's command line only (a PORT or PROJECT of the shell's environment is not)
given = $(if $(filter command line,$(origin $(1))),$($(1)))
start: setup
	node packages/cli/bin/contract.js serve "$(or $(call given,PROJECT),examples/tutorial)" $(if $(call given,PORT),--port "$(PORT)")

test: setup
	node scripts/run-tests.mjs

test-node-versions: setup
	bash scripts/test-node-versions.sh

pack-cli: setup
	npm run pack -w packages/cli

test-installed-cli: setup
	cd packages/cli && npx vitest run test/e2e/installed-cli.e2e.test.ts

bench: setup
	npm run bench

clean:
	$(MAKE) -C runtime clean
