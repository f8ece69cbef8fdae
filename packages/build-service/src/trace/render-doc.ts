/** Renders the "Trace records" table of docs/runtime-api.md from TRACE_KINDS (pure). */
import { TRACE_KINDS } from './record-kinds.js';

export const DOC_BEGIN = '<!-- BEGIN trace-records: generated from packages/build-service/src/trace/record-kinds.ts by `npm run docs:trace -w packages/build-service`; a test fails when stale -->';
export const DOC_END = '<!-- END trace-records -->';

const cell = (text: string) => text.replace(/\|/g, '\\|');

export function renderTraceTable(): string {
    return [
        DOC_BEGIN,
        '| kind (`event`) | area | fields | example line |',
        '|---|---|---|---|',
        ...TRACE_KINDS.map((k) => `| \`${k.kind}\` | ${k.area} | ${cell(k.fields)} | \`${cell(k.example)}\` |`),
        DOC_END,
    ].join('\n');
}

/** The doc with its generated section replaced (the markers must be there once). */
export function withTraceTable(doc: string): string {
    const b = doc.indexOf(DOC_BEGIN), e = doc.indexOf(DOC_END);
    if (b < 0 || e < b) throw new Error('docs/runtime-api.md lacks the trace-records markers');
    return doc.slice(0, b) + renderTraceTable() + doc.slice(e + DOC_END.length);
}
