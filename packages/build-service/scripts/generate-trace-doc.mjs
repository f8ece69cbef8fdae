// Regenerates the "Trace records" table of docs/runtime-api.md from src/trace/record-kinds.ts (built).
import { readFileSync, writeFileSync } from 'node:fs';
import { withTraceTable } from '../dist/trace/index.js';

const path = new URL('../../../docs/runtime-api.md', import.meta.url);
writeFileSync(path, withTraceTable(readFileSync(path, 'utf8')));
