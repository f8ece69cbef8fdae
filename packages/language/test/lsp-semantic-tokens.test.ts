/** Semantic highlighting (docs/ide.md "Editor services"): keywords, types, modules, schemas, ports (by index too), labels. */
import { SemanticTokensDecoder, type AbstractSemanticTokenProvider } from 'langium/lsp';
import { describe, expect, it } from 'vitest';
import { build } from './helpers.js';
import { ARCHITECTURE } from './lsp-workspace.js';

/** `text:type` of every token of a file, in order (and no two tokens at one place). */
async function tokens(file: string): Promise<string[]> {
    const ws = await build(ARCHITECTURE);
    const doc = ws.docs.get(file)!;
    const provider = ws.services.lsp.SemanticTokenProvider as AbstractSemanticTokenProvider;
    const result = await provider.semanticHighlight(doc, { textDocument: { uri: doc.uri.toString() } });
    const decoded = SemanticTokensDecoder.decode(result, provider.tokenTypes, doc);
    expect(new Set(decoded.map((t) => t.offset)).size).toBe(decoded.length);
    return decoded.map((t) => `${t.text}:${t.tokenType}`);
}

describe('semantic tokens', () => {
    it('classifies a schema: keywords, module names, ports by index, schema and parameter names, time values', async () => {
        const list = await tokens('schema.contract');
        expect(list).toEqual(expect.arrayContaining([
            'periodic:keyword', 'schema:keyword', 'cmd:namespace', 'consigne:parameter', 'TypeA:type',
            'realtime:keyword', 'PERIOD:property', '10ms:number', 'modules:keyword', 'MSA:class', 'MSC:class',
            'scheduling:keyword', 'graph:keyword', 'communications:keyword', '0:property', '2:property', 'import:keyword'
        ]));
        expect(list.filter((t) => t.endsWith(':class')).map((t) => t.split(':')[0])).toEqual(['MSA', 'MSC', 'MSD', 'MSA', 'MSC', 'MSA', 'MSC', 'MSC', 'MSD']);
    });

    it('classifies a supervisor: rule labels (label) at declarations and in started/endof, functions, variables, fields', async () => {
        const list = await tokens('sup.contract');
        expect(list.filter((t) => t.endsWith(':label'))).toEqual(['FIRST:label', 'SECOND:label', 'FIRST:label', 'SECOND:label']);
        expect(list).toEqual(expect.arrayContaining([
            'supervisor:keyword', 'SUP:class', 'go:method', 'local:keyword', 'rules:keyword', 'elapsed:keyword', '1ms:number',
            'subscribe:keyword', 'activate:keyword', 'failure_data:variable', 'target:variable', 'k:property', 'doit:function',
            'int:type', 'endof:keyword', 'started:keyword'
        ]));
        expect(list).not.toContain('int:keyword');
    });

    it('declares the label token type in the legend after the standard types', async () => {
        const ws = await build({});
        const provider = ws.services.lsp.SemanticTokenProvider as AbstractSemanticTokenProvider;
        const legend = provider.semanticTokensOptions.legend.tokenTypes;
        expect(legend.at(-1)).toBe('label');
        expect(legend.indexOf('label')).toBe(provider.tokenTypes['label']);
    });
});
