/** Output formats of diagnostics: gcc-like text, the JSON of the CLI contract, SARIF 2.1.0. */
import { pathToFileURL } from 'node:url';
import type { WorkspaceDiagnostic } from '@contract-studio/language/node';
import type { findCode } from '@contract-studio/language';
import { safeName } from './terminal-text.js';

/** `file:line:col severity code message`, one per line (newlines in messages are flattened; the file name's escaped, terminal-text.ts safeName). */
export function formatText(diagnostics: WorkspaceDiagnostic[], displayPath: (file: string) => string = (f) => f): string {
    return diagnostics
        .map((d) => `${safeName(displayPath(d.file))}:${d.line}:${d.column} ${d.severity} ${d.code} ${d.message.replace(/\s*\n\s*/g, ' ')}\n`)
        .join('');
}

export function formatJson(diagnostics: WorkspaceDiagnostic[]): string {
    const list = diagnostics.map((d) => ({ file: d.file, line: d.line, column: d.column, severity: d.severity, code: d.code, message: d.message }));
    return JSON.stringify({ diagnostics: list }, null, 2) + '\n';
}

const SARIF_LEVEL: Record<string, string> = { error: 'error', warning: 'warning', info: 'note', hint: 'note' };

/** `describe`: the language's findCode (passed in: importing the language here would load it for every command). */
export function formatSarif(diagnostics: WorkspaceDiagnostic[], dir: string, describe: typeof findCode): string {
    const ruleIds = [...new Set(diagnostics.map((d) => d.code))].sort();
    const log = {
        version: '2.1.0',
        $schema: 'https://json.schemastore.org/sarif-2.1.0.json',
        runs: [{
            tool: {
                driver: {
                    name: 'contract check',
                    informationUri: 'https://github.com/contract-studio',
                    rules: ruleIds.map((id) => ({ id, shortDescription: { text: describe(id)?.description ?? id } }))
                }
            },
            originalUriBaseIds: { SRCROOT: { uri: pathToFileURL(dir.endsWith('/') ? dir : dir + '/').href } },
            results: diagnostics.map((d) => ({
                ruleId: d.code,
                level: SARIF_LEVEL[d.severity] ?? 'note',
                message: { text: d.message },
                locations: [{
                    physicalLocation: {
                        artifactLocation: { uri: d.file, uriBaseId: 'SRCROOT' },
                        region: { startLine: d.line, startColumn: d.column, endLine: d.endLine, endColumn: d.endColumn }
                    }
                }]
            }))
        }]
    };
    return JSON.stringify(log, null, 2) + '\n';
}

/** `2 errors, 1 warning, 0 hints` style summary. */
export function summarize(diagnostics: WorkspaceDiagnostic[]): string {
    const count = (s: string) => diagnostics.filter((d) => d.severity === s).length;
    const plural = (n: number, word: string) => `${n} ${word}${n === 1 ? '' : 's'}`;
    const parts = [plural(count('error'), 'error'), plural(count('warning'), 'warning')];
    const infos = count('info');
    if (infos) parts.push(plural(infos, 'info'));
    parts.push(plural(count('hint'), 'hint'));
    return parts.join(', ');
}
