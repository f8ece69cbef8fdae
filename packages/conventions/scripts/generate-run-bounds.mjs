#!/usr/bin/env node
// Writes runtime/launcher/run_bounds.h from src/run-bounds.ts (runBoundsHeader): the launcher's
// module bound, the one number the launcher, `contract check` and the docs share.
//   npm run run-bounds -w packages/conventions   (builds dist first)
import { writeFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { runBoundsHeader } from '../dist/run-bounds.js';

const target = fileURLToPath(new URL('../../../runtime/launcher/run_bounds.h', import.meta.url));
writeFileSync(target, runBoundsHeader());
console.log(`wrote ${target}`);
