/**
 * Generate All on a workspace that is the project itself (`contract serve examples/tutorial`)
 * finishing a terminal rename killed half-way: its entry in the Generate panel names the files it
 * wrote exactly as they are called, and each file it left as it was gets its own entry.
 */
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { cpSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { GenerateResponse } from './api-types.js';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';

const TUTORIAL = join(fileURLToPath(new URL('../../..', import.meta.url)), 'examples/tutorial');

let server: TempIdeServer;
beforeAll(async () => {
  server = await startTempIdeServer('ide-generate-journal-', {
    prepare: (_base, ws) => {
      cpSync(TUTORIAL, ws, { recursive: true, filter: (src) => !/\/(src-gen|logs)$/.test(src) });
      // a file name a terminal shows as it is: two spaces first
      writeFileSync(join(ws, '  notes.contract'), '// notes on MSC\nimport "smodule3.contract";\n');
    },
  });
});
afterAll(() => server.close());

async function generate(): Promise<{ status: number; body: GenerateResponse }> {
  const res = await fetch(`${server.ide.url}/api/generate`, { method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': server.ide.token }, body: JSON.stringify({ project: '' }) });
  return { status: res.status, body: (await res.json()) as GenerateResponse };
}

describe('Generate All finishing an interrupted rename of the workspace\'s own project', () => {
  it('one entry naming the written files as they are called, one per file left as it was', async () => {
    const ws = server.ws;
    expect((await generate()).status).toBe(200);
    const codegen = await import('@contract-studio/codegen');
    const files = readdirSync(ws).filter((f) => f.endsWith('.contract')).sort().flatMap((f) => {
      const text = readFileSync(join(ws, f), 'utf8');
      const after = text.replace(/\bMSC\b/g, 'MSK');
      return after === text ? [] : [{ path: f, before: codegen.sha256(Buffer.from(text, 'utf8')), after }];
    });
    expect(files.map((f) => f.path)).toContain('  notes.contract');
    codegen.writeRenameJournal(join(ws, 'src-gen'), { version: 1, kind: 'module', oldName: 'MSC', newName: 'MSK', generatedNames: true, identifiers: [], files });
    await codegen.renameInGeneratedTree(join(ws, 'src-gen'), 'MSC', 'MSK');
    // typed meanwhile in one of them: left as it is, said on its own
    writeFileSync(join(ws, 'sched.contract'), `${readFileSync(join(ws, 'sched.contract'), 'utf8')}// typed meanwhile\n`);

    const r = await generate();
    expect(r.status).toBe(200);
    const written = files.map((f) => f.path).filter((f) => f !== 'sched.contract');
    expect(r.body.warnings.filter((w) => w.file === '.contract-rename.json')).toEqual([
      { file: '.contract-rename.json', message: `finished the rename of module MSC -> MSK that was interrupted (its journal src-gen/.contract-rename.json): ${written.length} file(s) written, 0 already renamed (${written.join(', ')})` },
      { file: '.contract-rename.json', message: 'sched.contract changed since the rename began (or is gone): left as it is; rename MSC there by hand' },
    ]);
    expect(readFileSync(join(ws, '  notes.contract'), 'utf8')).toBe('// notes on MSK\nimport "smodule3.contract";\n');
  });
});
