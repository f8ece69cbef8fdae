/** Outline (docs/ide.md "Editor services"): document symbols of every kind of element. */
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { EmptyFileSystem } from 'langium';
import { expectSymbols } from 'langium/test';
import { describe, expect, it } from 'vitest';
import type { DocumentSymbol } from 'vscode-languageserver-protocol';
import { createCactalServices } from '../src/cactal-module.js';
import { build } from './helpers.js';
import { ARCHITECTURE } from './lsp-workspace.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));

/** `name (detail)` lines, children indented. */
function outline(symbols: DocumentSymbol[], depth = 0): string[] {
    return symbols.flatMap((s) => [`${'  '.repeat(depth)}${s.name}${s.detail ? ` (${s.detail})` : ''}`, ...outline(s.children ?? [], depth + 1)]);
}

describe('outline', () => {
    it('lists datatypes with fields and functions (Langium expectSymbols)', async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        await expectSymbols(services)({
            text: 'datatype T {int a = 1, float b};\nfunction bool ok(string s, T t);',
            assert: (symbols) => {
                expect(outline(symbols)).toEqual(['T (datatype)', '  a (int)', '  b (float)', 'ok (bool (string s, T t))']);
                expect(symbols.map((x) => x.kind)).toEqual([23, 12]); // Struct, Function
                expect(symbols[0]!.children!.map((x) => x.kind)).toEqual([8, 8]); // Field
            }
        });
    });

    it('lists a module with its parameters and ports (direction, kind, index, type)', async () => {
        const ws = await build(ARCHITECTURE);
        const doc = ws.docs.get('msc.contract')!;
        const symbols = await ws.services.lsp.DocumentSymbolProvider!.getSymbols(doc, { textDocument: { uri: doc.uri.toString() } });
        expect(outline(symbols)).toEqual([
            'MSC (synchronous module, C=1ms)',
            '  consigne (parameter :0 TypeA)',
            '  in_coordinates (in data :0 TypeA)',
            '  command (out data :1 TypeB)',
            '  failing (out event :1 TypeD)'
        ]);
        // the selection is the name, the range the whole module
        expect(symbols[0]!.selectionRange.start).toEqual({ line: 1, character: 19 });
        expect(symbols[0]!.range.start).toEqual({ line: 1, character: 0 });
    });

    it('lists a schema with parameters, modules and communications, and the scheduler configuration', async () => {
        const ws = await build({ ...ARCHITECTURE, 'sched.contract': 'import "msa.contract";\nimport "schema.contract";\nscheduler configuration { modules { MSA; } schemas { cmd; } }' });
        const get = async (file: string) => {
            const doc = ws.docs.get(file)!;
            return outline(await ws.services.lsp.DocumentSymbolProvider!.getSymbols(doc, { textDocument: { uri: doc.uri.toString() } }));
        };
        expect(await get('schema.contract')).toEqual([
            'cmd (periodic schema, PERIOD=10ms)',
            '  consigne (TypeA)',
            '  MSA (module)', '  MSC (module)', '  MSD (module)',
            '  MSA:0 -> MSC:0 (data * 1)', '  MSC:1 -> MSD:2 (data * 2)'
        ]);
        expect(await get('sched.contract')).toEqual([
            'scheduler configuration', '  MSA (scheduled module)', '  cmd (scheduled schema)'
        ]);
    });

    it('lists the tutorial supervisor with its ports, function, locals and rules', async () => {
        const ws = await build({ 'supervisor.contract': readFileSync(`${TUTORIAL}/supervisor.contract`, 'utf8') });
        const doc = ws.docs.get('supervisor.contract')!;
        const lines = outline(await ws.services.lsp.DocumentSymbolProvider!.getSymbols(doc, { textDocument: { uri: doc.uri.toString() } }));
        expect(lines.slice(0, 6)).toEqual([
            'SUP (supervisor)',
            '  message_received (in event :1 TypeC)',
            '  connection_status (in event :2 string)',
            '  failure (in event :3 TypeD)',
            '  failure_message_type (out event :1 string)',
            '  action ((TypeA consigne))'
        ]);
        expect(lines.filter((l) => l.endsWith('(rule)')).map((l) => l.trim())).toEqual(
            ['FIRST (rule)', 'SECOND (rule)', 'THIRD (rule)', 'FOURTH (rule)', 'RECEPTION (rule)']);
        expect(lines).toContain('    temp_consigne (local TypeA)');
    });
});
