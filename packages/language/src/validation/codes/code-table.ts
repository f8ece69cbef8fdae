/**
 * Diagnostic codes. Every diagnostic the Cactal language reports has a stable code declared in a
 * per-area table (`codes/<area>.ts`) with its severity, what it means and an example that raises it.
 * `codes/index.ts` aggregates the tables; `docs/diagnostics.md` is generated from them
 * (`npm run docs:diagnostics -w packages/language`) and a test fails when it is stale.
 */
export type Severity = 'error' | 'warning' | 'info' | 'hint';

export interface DiagnosticCode {
    /** Stable identifier, kebab-case, prefixed by its area (`import-missing-file`). */
    readonly code: string;
    readonly severity: Severity;
    /** What it means and what would be right. */
    readonly description: string;
    /** A Cactal snippet (or file set) that raises it. */
    readonly example: string;
}

export interface CodeArea {
    /** Section title in docs/diagnostics.md. */
    readonly title: string;
    /** The docs/ page and section that states the rules the area checks (`language-reference.md §1`). */
    readonly reference: string;
    readonly codes: readonly DiagnosticCode[];
}

type Entry = Omit<DiagnosticCode, 'code'>;

/**
 * Declares an area's codes: `defineCodes('Imports', 'language-reference.md §1', { 'import-cycle': {...} })` returns
 * the area (for the doc) and a map code -> DiagnosticCode (for the validators).
 */
export function defineCodes<K extends string>(title: string, reference: string, entries: Record<K, Entry>):
    { area: CodeArea; codes: Record<K, DiagnosticCode> } {
    const codes = {} as Record<K, DiagnosticCode>;
    for (const key of Object.keys(entries) as K[]) {
        codes[key] = { code: key, ...entries[key] };
    }
    return { area: { title, reference, codes: Object.values(codes) }, codes };
}
