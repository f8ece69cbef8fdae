import { readFileSync } from 'node:fs';
import { generateFiles } from '@contract-studio/codegen';
const arch = JSON.parse(readFileSync('/tmp/synth-arch.json', 'utf8'));
for (let i = 0; i < 4; i++) { const t = performance.now(); generateFiles(arch, { runtimeFromArchitecture: '/x' }); console.log(performance.now() - t); }
