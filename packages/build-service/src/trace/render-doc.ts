/** Renders the "Trace records" table of docs/runtime-api.md from TRACE_KINDS (pure). */
import { TRACE_KINDS } from './record-kinds.js';
import { fieldJsonType, fieldKeysOf } from './field-types.js';

export const DOC_BEGIN = '<!-- BEGIN trace-records: generated from packages/build-service/src/trace/record-kinds.ts by `npm run docs:trace -w packages/build-service`; a test fails when stale -->';
export const DOC_END = '<!-- END trace-records -->';

const cell = (text: string) => text.replace(/\|/g, '\\|');

/** A kind's `fields` keys with their JSON types, for the doc. */
function fieldsCell(kind: string): string {
    if (kind === 'sup_rule') return 'none: `function`, `rule` (strings), `active` (boolean), `cause` (string) and `causeEvent` (an object) are top-level';
    const keys = fieldKeysOf(kind);
    if (kind === 'user') return `${keys.map((key) => `\`${key}\` (${fieldJsonType(key) ?? '?'})`).join(', ')}: the name the module logged, and the engine kind it posed as (a module's record under ORD's or a supervisor's kind); the detail's \`key=value\` words are not parsed into \`fields\` (a module's own words: read \`detail\`)`;
    if (!keys.length) return 'none (`{}`): read the detail';
    const typed = keys.map((key) => `\`${key}\` (${fieldJsonType(key) ?? '?'})`).join(', ');
    return kind === 'scheduler' || kind === 'supervisor' ? `${typed}: \`what\` always, the others as the line names them (the table above says which line has which)` : typed;
}

export function renderTraceTable(): string {
    return [
        DOC_BEGIN,
        '| kind (`event`) | area | fields | example line |',
        '|---|---|---|---|',
        ...TRACE_KINDS.map((k) => `| \`${k.kind}\` | ${k.area} | ${cell(k.fields)} | \`${cell(k.example)}\` |`),
        '',
        'The `fields` of each kind in `contract trace --format json` and `contract run --trace` (field-types.ts): each key has one JSON type whatever its value\'s size, a number written with its exact digits or a string; a key the line does not hold is left out (a number key whose word is not an integer too).',
        '',
        '| kind | `fields` keys (JSON type) |',
        '|---|---|',
        ...TRACE_KINDS.map((k) => `| \`${k.kind}\` | ${fieldsCell(k.kind)} |`),
        DOC_END,
    ].join('\n');
}

/** The doc with its generated section replaced (the markers must be there once). */
export function withTraceTable(doc: string): string {
    const b = doc.indexOf(DOC_BEGIN), e = doc.indexOf(DOC_END);
    if (b < 0 || e < b) throw new Error('docs/runtime-api.md lacks the trace-records markers');
    return doc.slice(0, b) + renderTraceTable() + doc.slice(e + DOC_END.length);
}
