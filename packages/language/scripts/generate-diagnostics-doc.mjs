#!/usr/bin/env node
// Writes docs/diagnostics.md (repository root) from the compiled diagnostic code tables.
import { writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { CODE_AREAS, renderDiagnosticsDoc } from '../dist/validation/codes/index.js';

const target = fileURLToPath(new URL('../../../docs/diagnostics.md', import.meta.url));
writeFileSync(target, renderDiagnosticsDoc(CODE_AREAS));
console.log(`wrote ${target}`);
