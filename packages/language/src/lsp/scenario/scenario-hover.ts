/**
 * Hover in a `.scenario` file (docs/simulation.md "Editing scenarios"): on a `MODULE:PORT` the
 * port's type and its declaration (file and line), on a module/supervisor/function its kind and
 * ports/parameters, on a rule its precondition and postcondition, on a schema periodic/event and
 * its PERIOD/CRITICAL_DELAY, on a local its type and owner, on a time (`t=300ms`) its value in µs.
 * Positions come from the simulator's own parser (`parseScenario` spans). Never throws.
 */
import { AstUtils, type AstNode } from 'langium';
import type { Hover, Position, Range } from 'vscode-languageserver-types';
import { isModule, type Module, type Port, type Rule, type Schema, type Supervisor, type SupervisionFunction } from '../../generated/ast.js';
import { computeTimeNs, criticalDelayNs, localsOf, periodNs, rulesOf } from '../../model/blocks.js';
import { portsOfKind } from '../../model/ports.js';
import { typeName, typeOf } from '../../model/types.js';
import { parseScenario, parseTimeLiteral, type Name, type SourceSpan, type Step } from '../../scenario/parse.js';
import type { ScenarioNames } from './scenario-names.js';

/** Longest declaration text quoted in a hover (a rule's condition can be long). */
const MAX_QUOTE = 600;

function inSpan(span: SourceSpan, line: number, character: number): boolean {
    return span.line === line + 1 && character >= span.column - 1 && character <= span.endColumn - 1;
}

function toRange(span: SourceSpan): Range {
    return { start: { line: span.line - 1, character: span.column - 1 }, end: { line: span.line - 1, character: span.endColumn - 1 } };
}

function quote(node: AstNode | undefined): string {
    const text = node?.$cstNode?.text?.replace(/\s+/g, ' ').trim() ?? '';
    return text.length > MAX_QUOTE ? `${text.slice(0, MAX_QUOTE)} ...` : text;
}

/** `amodule1.contract:12` for a declaration. */
function where(node: AstNode): string {
    try {
        const uri = AstUtils.getDocument(node).uri.path;
        const file = uri.slice(uri.lastIndexOf('/') + 1);
        const line = node.$cstNode ? node.$cstNode.range.start.line + 1 : undefined;
        return line ? `${file}:${line}` : file;
    } catch {
        return '';
    }
}

function micro(ns: number): string {
    const us = ns / 1000;
    return `${us.toLocaleString('en-US', { maximumFractionDigits: 3 })} µs`;
}

const timeText = (ns: number | undefined) => (ns === undefined ? 'not set' : `${micro(ns)}`);

function moduleHover(m: Module): string {
    const ports = portsOfKind(m, 'event', 'out').map((p) => `:${p.index} ${typeName(typeOf(p.type))} ${p.name}`);
    const c = m.kind === 'synchronous' ? `, C = ${timeText(computeTimeNs(m))}` : '';
    return `**${m.kind} module ${m.name}**${c} (${where(m)})\n\nout event ports: ${ports.length ? ports.join(', ') : 'none'}`;
}

function supervisorHover(s: Supervisor): string {
    return `**supervisor ${s.name}** (${where(s)})\n\nfunctions: ${s.functions.map((f) => f.name).join(', ') || 'none'}`;
}

function functionHover(s: Supervisor, f: SupervisionFunction): string {
    const params = f.parameters.map((p) => `${typeName(typeOf(p.type))} ${p.name}`).join(', ');
    return `**supervision function ${s.name}.${f.name}(${params})** (${where(f)})\n\nrules: ${rulesOf(f).map((r) => r.name).join(', ') || 'none'}`;
}

function portHover(owner: string, p: Port): string {
    return `**${owner}:${p.index}**: out event port of \`${owner}\`, type \`${typeName(typeOf(p.type))}\`\n\n\`\`\`cactal\n${quote(p)}\n\`\`\`\ndeclared at ${where(p)}`;
}

function ruleHover(s: Supervisor, f: SupervisionFunction, r: Rule): string {
    return `**rule ${s.name}.${f.name}.${r.name}** (${where(r)})\n\nprecondition: \`${quote(r.precondition)}\`\n\npostcondition: \`${quote(r.postcondition)}\``;
}

function schemaHover(s: Schema): string {
    if (s.kind === 'periodic') return `**periodic schema ${s.name}** (${where(s)})\n\nPERIOD = ${timeText(periodNs(s))}, CRITICAL_DELAY = ${timeText(criticalDelayNs(s))}`;
    return `**event schema ${s.name}** (${where(s)}): activated by a supervisor, its modules run while it is active`;
}

export function scenarioHover(text: string, position: Position, names: ScenarioNames): Hover | null {
    try {
        return hoverUnguarded(text, position, names);
    } catch {
        return null;
    }
}

/** The hover itself; `scenarioHover` guards it (exported for the property test, which must see a throw). */
export function hoverUnguarded(text: string, position: Position, names: ScenarioNames): Hover | null {
    const lineText = text.split(/\r?\n/)[position.line];
    if (lineText === undefined || lineText.length > 4096) return null;
    const { line, character } = position;

    // A time literal under the cursor (t=300ms, until 5s, expect at 1ms, exec M 2ms).
    const token = /\S*$/.exec(lineText.slice(0, character))![0] + /^\S*/.exec(lineText.slice(character))![0];
    const timeText = token.replace(/^t\s*=/, '');
    const ns = /^[0-9.]+(ns|us|ms|s)$|^0$/.test(timeText) ? parseTimeLiteral(timeText) : undefined;
    if (ns !== undefined) {
        const start = character - /\S*$/.exec(lineText.slice(0, character))![0].length + (token.length - timeText.length);
        return {
            contents: { kind: 'markdown', value: `**${timeText}** = ${micro(ns)} (${ns.toLocaleString('en-US')} ns) of virtual time` },
            range: { start: { line, character: start }, end: { line, character: start + timeText.length } },
        };
    }

    const step: Step | undefined = parseScenario(text).steps.find((s) => s.span.line === line + 1);
    if (!step) return null;
    const at = (n: Name | undefined) => n !== undefined && inSpan(n.span, line, character);
    const answer = (value: string, span: SourceSpan): Hover => ({ contents: { kind: 'markdown', value }, range: toRange(span) });
    const supOf = (n: Name) => names.supervisors.get(n.text);
    const fnOf = (s: Supervisor | undefined, n: Name) => s?.functions.find((f) => f.name === n.text);

    switch (step.kind) {
        case 'event': {
            const src = step.module.text;
            const owner: Module | Supervisor | undefined = names.modules.get(src) ?? names.supervisors.get(src);
            if (at(step.module)) {
                if (src === 'ORD') return answer('**ORD**, the scheduler: ORD:0 "schema" is a deadline miss, ORD:1 "schema" a conflict; every supervisor receives them', step.module.span);
                return owner ? answer(isModule(owner) ? moduleHover(owner) : supervisorHover(owner), step.module.span) : null;
            }
            if (inSpan(step.portSpan, line, character) || at(step.portName)) {
                if (src === 'ORD') return answer(step.port === 0 ? '**ORD:0**: deadline miss of the schema named by the value' : '**ORD:1**: conflict of the schema named by the value', step.portSpan);
                const p = owner && portsOfKind(owner, 'event', 'out').find((x) => x.index === step.port);
                return p ? answer(portHover(src, p), at(step.portName) ? step.portName!.span : step.portSpan) : null;
            }
            if (step.value && inSpan(step.value.span, line, character) && src === 'ORD' && step.value.kind === 'string') {
                const s = names.schemas.get(step.value.value);
                return s ? answer(schemaHover(s), step.value.span) : null;
            }
            return null;
        }
        case 'start':
        case 'stop': {
            const s = supOf(step.supervisor);
            if (at(step.supervisor)) return s ? answer(supervisorHover(s), step.supervisor.span) : null;
            const f = fnOf(s, step.function);
            if (at(step.function)) return s && f ? answer(functionHover(s, f), step.function.span) : null;
            if (step.kind === 'start') {
                for (const a of step.args) {
                    if (!at(a.name)) continue;
                    const p = f?.parameters.find((x) => x.name === a.name.text);
                    return p ? answer(`**${typeName(typeOf(p.type))} ${p.name}**: parameter of ${step.supervisor.text}.${f!.name}${p.value ? ` (default ${quote(p.value)})` : ''}`, a.name.span) : null;
                }
            }
            return null;
        }
        case 'crash':
        case 'finish':
        case 'exec': {
            const m = names.modules.get(step.module.text);
            return at(step.module) && m ? answer(moduleHover(m), step.module.span) : null;
        }
        case 'expect': {
            const e = step.expectation;
            switch (e.kind) {
                case 'rule':
                case 'function': {
                    const s = supOf(e.supervisor);
                    if (at(e.supervisor)) return s ? answer(supervisorHover(s), e.supervisor.span) : null;
                    const f = fnOf(s, e.function);
                    if (at(e.function)) return s && f ? answer(functionHover(s, f), e.function.span) : null;
                    if (e.kind === 'rule' && at(e.rule)) {
                        const r = f && rulesOf(f).find((x) => x.name === e.rule.text);
                        return s && f && r ? answer(ruleHover(s, f, r), e.rule.span) : null;
                    }
                    return null;
                }
                case 'schema':
                case 'count': {
                    const s = names.schemas.get(e.schema.text);
                    return at(e.schema) && s ? answer(schemaHover(s), e.schema.span) : null;
                }
                case 'module': {
                    const m = names.modules.get(e.module.text);
                    return at(e.module) && m ? answer(moduleHover(m), e.module.span) : null;
                }
                case 'local': {
                    if (e.supervisor && at(e.supervisor)) {
                        const s = supOf(e.supervisor);
                        return s ? answer(supervisorHover(s), e.supervisor.span) : null;
                    }
                    if (e.supervisor && e.function && at(e.function)) {
                        const s = supOf(e.supervisor);
                        const f = fnOf(s, e.function);
                        return s && f ? answer(functionHover(s, f), e.function.span) : null;
                    }
                    if (!at(e.local)) return null;
                    for (const s of names.supervisors.values()) {
                        if (e.supervisor && s.name !== e.supervisor.text) continue;
                        for (const f of s.functions) {
                            if (e.function && f.name !== e.function.text) continue;
                            const l = localsOf(f).find((x) => x.name === e.local.text);
                            if (l) return answer(`**${typeName(typeOf(l.type))} ${l.name}**: local of ${s.name}.${f.name} (${where(l)})`, e.local.span);
                        }
                    }
                    return null;
                }
            }
        }
    }
    return null;
}
