#!/usr/bin/env node
// `contract-language-server [--stdio]`: the Cactal language server for any LSP editor (docs/editors.md),
// installed with the CLI. It is the language package's server (@contract-studio/language/server).
await import('@contract-studio/language/server');
