#!/usr/bin/env node
// Builds the extension's files from the workspace (run `npm run build` at the root first, for the
// language package's dist/): dist/extension.js (the client, `vscode` left to the editor),
// dist/server.js (the stdio language server, packages/language/dist/node/main.js, with all its
// dependencies: one file, no node_modules in the .vsix) and syntaxes/ (the TextMate grammar the
// language package generates). `npm run package` then makes dist/cactal-vscode.vsix with vsce.
import { build } from 'esbuild';
import { cpSync, existsSync, mkdirSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const language = resolve(dirname(createRequire(import.meta.url).resolve('@contract-studio/language')), '..'); // dist/index.js -> the package
const serverEntry = join(language, 'dist', 'node', 'main.js');
if (!existsSync(serverEntry)) {
    process.stderr.write(`vscode: ${serverEntry} is missing: run \`npm run build\` at the repository root first\n`);
    process.exit(2);
}

const common = { bundle: true, platform: 'node', target: 'node20', format: 'cjs', sourcemap: false, logLevel: 'warning', legalComments: 'none' };
await build({ ...common, entryPoints: [join(here, 'src', 'extension.ts')], outfile: join(here, 'dist', 'extension.js'), external: ['vscode'] });
await build({ ...common, entryPoints: [serverEntry], outfile: join(here, 'dist', 'server.js') });

mkdirSync(join(here, 'syntaxes'), { recursive: true });
cpSync(join(language, 'syntaxes', 'cactal.tmLanguage.json'), join(here, 'syntaxes', 'cactal.tmLanguage.json'));
process.stdout.write('vscode: dist/extension.js, dist/server.js, syntaxes/cactal.tmLanguage.json\n');
