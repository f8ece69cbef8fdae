/** Renders docs/diagnostics.md from the code tables (pure: the caller writes the file). */
import type { CodeArea } from './code-table.js';

export function renderDiagnosticsDoc(areas: CodeArea[]): string {
    const lines: string[] = [
        '# Cactal diagnostics',
        '',
        '<!-- GENERATED from packages/language/src/validation/codes/*.ts by',
        '     `npm run docs:diagnostics -w packages/language`. Do not edit by hand: a test fails when this file is stale. -->',
        '',
        'Every diagnostic of the Cactal language server and of `contract check` has a stable code.',
        'Severities: **error** (the architecture cannot be generated; `contract check` exits 1),',
        '**warning** (probably wrong; does not fail `contract check`), **info**, and **hint** (a suggestion,',
        'such as an unused import; editors show it faded; it does not count as a warning).',
        '',
        '| code | severity | area |',
        '|---|---|---|',
        ...areas.flatMap((a) => a.codes.map((c) => `| [\`${c.code}\`](#${c.code}) | ${c.severity} | ${a.title} (${a.reference}) |`)),
        ''
    ];
    for (const area of areas) {
        lines.push(`## ${area.title} (${area.reference})`, '');
        for (const c of area.codes) {
            lines.push(`### ${c.code}`, '', `**${c.severity}** — ${c.description}`, '', '```cactal', c.example, '```', '');
        }
    }
    return lines.join('\n');
}
