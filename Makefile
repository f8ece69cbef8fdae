# ContrACT Studio — top-level entry points. See README.md.
#   make start   install what is missing, build, and serve the IDE + build service on the tutorial
#   make test    install what is missing, build, and run every test (TypeScript, C, browser, sandboxes)
#   make bench   run every benchmark, write bench/results.json
#   make test-node-versions   CLI smoke + language/codegen tests on Node 22 and 24 (several minutes: not in make test)
.PHONY: setup start test test-ts test-c test-node-versions bench clean

setup:
	bash scripts/setup.sh

start: setup
	node packages/cli/bin/contract.js serve examples/tutorial

test: setup
	node scripts/run-tests.mjs

test-node-versions: setup
	bash scripts/test-node-versions.sh

bench: setup
	npm run bench

clean:
	$(MAKE) -C runtime clean
