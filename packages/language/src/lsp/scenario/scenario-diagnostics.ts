/**
 * LSP diagnostics of a `.scenario` text: the simulator's own parser and model checks
 * (`@contract-studio/language/scenario`, the code behind `contract simulate`), turned into LSP
 * ranges (their spans are 1-based with an exclusive end column; LSP is 0-based). Never throws.
 */
import { DiagnosticSeverity, type Diagnostic } from 'vscode-languageserver-types';
import { checkScenario, indexModels } from '../../scenario/model-check.js';
import { parseScenario, type ScenarioDiagnostic } from '../../scenario/parse.js';
import type { ScenarioProject } from './scenario-project.js';

export const SCENARIO_DIAGNOSTIC_SOURCE = 'cactal-scenario';

function toLsp(d: ScenarioDiagnostic): Diagnostic {
    const line = Math.max(0, d.line - 1);
    const start = Math.max(0, d.column - 1);
    return {
        range: { start: { line, character: start }, end: { line, character: Math.max(start, d.endColumn - 1) } },
        severity: d.severity === 'warning' ? DiagnosticSeverity.Warning : DiagnosticSeverity.Error,
        code: d.code,
        source: SCENARIO_DIAGNOSTIC_SOURCE,
        message: d.message,
        data: { code: d.code },
    };
}

export function scenarioDiagnostics(text: string, project: ScenarioProject): Diagnostic[] {
    try {
        const parsed = parseScenario(text);
        const out = parsed.diagnostics.map(toLsp);
        if (!project.models.length) {
            out.push(toLsp({
                line: 1, column: 1, endColumn: 2, severity: 'warning', code: 'scenario-no-project',
                message: 'no .contract file in this folder or above it: names and values are not checked (contract simulate DIR takes the project folder)',
            }));
            return out;
        }
        out.push(...checkScenario(parsed.steps, indexModels(project.models)).diagnostics.map(toLsp));
        return out;
    } catch (e) {
        // The parser and the checker never throw by design; a model in the middle of an edit must not
        // take the server down either.
        return [{
            range: { start: { line: 0, character: 0 }, end: { line: 0, character: 1 } }, severity: DiagnosticSeverity.Error,
            code: 'scenario-internal', source: SCENARIO_DIAGNOSTIC_SOURCE, message: `the scenario could not be checked (${e instanceof Error ? e.message : String(e)})`,
        }];
    }
}
