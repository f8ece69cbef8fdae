#!/usr/bin/env node
/**
 * `contract-language-server`: the Cactal language server over stdio (or any transport
 * vscode-languageserver reads from the command line: --stdio, --node-ipc, --socket=N), for any
 * LSP editor. Files are read from disk (imports resolve relative to the importing file).
 * `.scenario` files (language id `cactal-scenario`) get diagnostics, completion and hover
 * (docs/simulation.md "Editing scenarios").
 */
import { startLanguageServer } from 'langium/lsp';
import { NodeFileSystem } from 'langium/node';
import { createConnection, ProposedFeatures } from 'vscode-languageserver/node.js';
import { createCactalServices } from '../cactal-module.js';
import { addScenarioSupport } from '../lsp/scenario/scenario-server.js';
import { followImportsWithoutFolders } from './follow-imports.js';
import { isTreeFolder } from './load-workspace.js';
import { watchTreeFolders } from './tree-folder-watcher.js';
import { SRC_GEN_DIR } from '@contract-studio/conventions';
import { join } from 'node:path';

if (!process.argv.some((a) => a === '--stdio' || a === '--node-ipc' || a.startsWith('--socket') || a.startsWith('--pipe'))) {
    process.argv.push('--stdio');
}
const connection = createConnection(ProposedFeatures.all);
const { shared, Cactal } = createCactalServices({ connection, ...NodeFileSystem });
// the projects of the workspace folders (scoping/projects.ts): a generated tree is a real folder, as generate has it
Cactal.projects.Projects.configure({ probe: (folder) => isTreeFolder(join(folder.fsPath, SRC_GEN_DIR)) });
followImportsWithoutFolders(shared, Cactal);
// a src-gen/ made or removed on disk, for a client that watches no files for the server
watchTreeFolders(shared);
addScenarioSupport(shared);
startLanguageServer(shared);
