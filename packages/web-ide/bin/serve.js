#!/usr/bin/env node
// Starts the ContrACT Studio IDE on a workspace folder: `serve.js [DIR] [--port N] [--host ADDR]`.
import { fileURLToPath } from 'node:url';
import { runServe } from '../dist-server/index.js';

const tutorial = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));
process.exitCode = await runServe(process.argv.slice(2), tutorial);
